"""The load harness, small and bounded: 5 HTTP clients x 10 calls while sim nodes join and
leave every 50 ms — no errors, no hangs, the final list change reaches every client, and the
audit log holds one valid line per call."""

from __future__ import annotations

import pytest

from robovoice.mcp_server.bench_load import bench_load


async def test_five_clients_ten_calls_while_nodes_come_and_go() -> None:
    report = await bench_load(5, 10, churn_s=0.05, call_timeout_s=10.0)
    assert report.first_errors == []
    assert report.calls_done == 50 and report.errors == 0 and report.timeouts == 0
    assert report.final_list_changed_reached == 5
    assert report.audit_lines == 50 and report.audit_skipped_lines == 0
    assert report.ok and report.to_dict()["ok"] is True


@pytest.mark.integration
async def test_the_same_with_the_nodes_over_zenoh() -> None:
    report = await bench_load(5, 10, churn_s=0.05, call_timeout_s=10.0, middleware="zenoh")
    assert report.first_errors == [] and report.ok and report.middleware == "zenoh"
