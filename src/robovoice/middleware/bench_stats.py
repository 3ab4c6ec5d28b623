"""The one summary of call latencies that the middleware benchmarks (`bench zenoh`, `bench ros2`) report."""

from __future__ import annotations

import statistics
from dataclasses import dataclass

BLOCK = 50  # calls per interleaved block: the compared paths take turns, so load drifts hit both


@dataclass(frozen=True, slots=True)
class Stats:
    """Count, median and p95 (nearest rank) in milliseconds of durations in seconds."""

    n: int
    median_ms: float
    p95_ms: float

    @classmethod
    def of(cls, seconds: list[float]) -> Stats:
        ordered = sorted(seconds)
        p95 = ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))]
        return cls(len(ordered), statistics.median(ordered) * 1000, p95 * 1000)
