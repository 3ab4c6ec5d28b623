"""`bench_mcp` runs end to end and reports what `robovoice bench mcp` prints (numbers are not judged
here: benchmarks, not timed tests; only the memory flatness of snapshot ingest is checked)."""

from __future__ import annotations

import pytest

from robovoice.mcp_server.bench import bench_mcp, format_report


@pytest.mark.slow
async def test_bench_mcp_reports_every_series() -> None:
    report = await bench_mcp(10, ingest_seconds=0.5)
    for transport in ("inprocess", "stdio", "http", "http_2026"):
        echo = report[transport]["echo"]
        assert echo["robot"]["n"] == echo["plain"]["n"] == 10
        assert echo["robot"]["p50"] > 0 and echo["ratio_p50"] > 0
    for transport in ("inprocess", "http", "http_2026"):
        assert report[transport]["snapshot_vs_noop"]["snapshot"]["n"] == 10
    assert set(report["stdio"]["floor"]) == {"pipe"}
    for transport in ("http", "http_2026"):  # the floors are timed in the same blocks
        floor = report[transport]["floor"]
        assert set(floor) == {"http_echo", "tcp"}
        assert floor["http_echo"]["n"] == 10 and floor["http_echo"]["robot_ratio_p50"] > 0
        assert set(report[transport]["goals"]) == {"p50_within_ms", "within_floor_ratio"}
    rates = [row["rate_hz"] for row in report["ingest"]]
    assert rates == [1000, 10000]
    for row in report["ingest"]:
        assert row["published"] >= row["rate_hz"] * 0.4  # most of the half second's worth arrived
        assert row["tracemalloc_growth_kb"] < 512  # one slot per topic: flat, whatever the rate
    text = format_report(report)
    assert "stdio (child process)" in text and "10000 Hz" in text and "ratio p50" in text
    assert "HTTP echo" in text and "raw TCP round trip" in text and "bare pipe round trip" in text


async def test_bench_mcp_needs_enough_calls() -> None:
    with pytest.raises(ValueError, match="at least 10"):
        await bench_mcp(3)
