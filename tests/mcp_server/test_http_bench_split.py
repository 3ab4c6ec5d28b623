"""`bench_split` measures the five series against real servers (it prints numbers; nothing here
times anything): every call is checked for the right answer as it is made."""

from __future__ import annotations

import os
import time

import pytest

from robovoice.mcp_server.bench_inprocess import inprocess_split
from robovoice.mcp_server.bench_split import bench_split, format_split, server_cpu_s

SERIES = ["sdk_2025", "sdk_2026", "raw_2025", "raw_2026", "http_echo"]


async def test_every_series_is_measured_on_both_sides() -> None:
    report = await bench_split(n=5, rounds=2)
    assert list(report["series"]) == SERIES
    for row in report["series"].values():
        assert row["calls"] == 10
        assert row["p50_ms"] > 0 and row["mean_ms"] > 0
        assert row["client_cpu_ms"] >= 0 and row["server_cpu_ms"] >= 0
    text = format_split(report)
    assert all(name in text for name in SERIES) and report["load_before"] in text


def test_server_cpu_counts_this_process_working() -> None:
    before = server_cpu_s(os.getpid())
    deadline = time.process_time() + 0.05
    while time.process_time() < deadline:
        pass
    assert server_cpu_s(os.getpid()) > before


async def test_bad_counts_are_refused() -> None:
    with pytest.raises(ValueError, match="at least 1"):
        await bench_split(n=0)


async def test_the_server_side_alone_is_measured_in_process() -> None:
    cpu_ms = await inprocess_split(n=3, rounds=1)  # each response is checked as it comes back
    assert list(cpu_ms) == ["2025 session tools/call", "2026-07-28 tools/call", "HTTP echo app", "call_tool alone"]
    assert all(value > 0 for value in cpu_ms.values())
