"""The Zenoh benchmark runs end to end (tiny sizes; the numbers are not judged here)."""

from __future__ import annotations

import pytest

from robovoice.middleware.bench_zenoh import run_zenoh_bench

pytestmark = pytest.mark.integration


async def test_zenoh_bench_smoke() -> None:
    report = await run_zenoh_bench(calls=50, mcp_calls=50, ingest_messages=300)
    assert report.bare_get.n == 50 and report.rpc.n == 50 and report.rpc_ratio > 0
    assert report.rpc_over_bare_ms == report.rpc.median_ms - report.bare_get.median_ms
    assert isinstance(report.rpc_within_goal, bool)
    assert report.mcp_memory is not None and report.mcp_zenoh is not None and report.mcp_ratio is not None
    assert report.ingest is not None and report.ingest.sent == 300
    assert report.ingest.received == 300  # loopback, a small burst: nothing is dropped
    assert report.ingest.per_second > 0
    assert set(report.to_dict()) >= {"bare_get", "rpc", "rpc_ratio", "mcp_memory", "mcp_zenoh", "ingest"}
