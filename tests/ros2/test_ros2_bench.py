"""`robovoice bench ros2` runs and reports every figure (a smoke test: nothing here is timed)."""

from __future__ import annotations

import pytest

from robovoice.middleware.bench_ros2 import run_ros2_bench

from .ros2_testkit import RosWorld

pytestmark = pytest.mark.integration


async def test_the_ros2_bench_reports_every_figure(ros: RosWorld) -> None:
    report = await run_ros2_bench(domain=ros.domain, rounds=1, ingest_s=1.0)
    assert report.bare_rclpy.n == report.adapter_call.n == report.mcp_call.n == report.mcp_memory_call.n == 50
    assert report.mcp_session_call.n == report.mcp_session_memory_call.n == 50
    assert report.mcp_call.median_ms > 0 and report.ingest.received > 0
    assert 0 < report.kill_noticed_s < 10
