"""Process health during the soak: RSS, Python heap blocks, gc, fds, threads, asyncio tasks.

Cheap enough to take every few simulated minutes (tracemalloc would slow the whole run):
RSS from /proc/self/statm (and without file-backed pages, RssAnon), `sys.getallocatedblocks()`
for the Python heap, `gc.get_count()` and the number of gc-tracked objects (after a full
collection, so garbage is not counted; see `tracked_objects`), open file descriptors from
/proc/self/fd, `threading.active_count()`, `len(asyncio.all_tasks())`.
"""

from __future__ import annotations

import asyncio
import gc
import os
import resource
import sys
import threading
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from typing import Any

_PAGE = os.sysconf("SC_PAGE_SIZE") if hasattr(os, "sysconf") else 4096


@dataclass(frozen=True, slots=True)
class Sample:
    """One look at the process at simulated time `sim_s` (wall time `wall_s` into the run)."""

    sim_s: float
    wall_s: float
    rss_mib: float
    heap_blocks: int
    gc_objects: int
    gc_counts: tuple[int, int, int]
    fds: int
    threads: int
    tasks: int
    rss_anon_mib: float = 0.0  # RSS without file-backed pages (the model's memory-mapped weights)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def rss_mib() -> float:
    try:
        with open("/proc/self/statm", encoding="ascii") as f:
            return int(f.read().split()[1]) * _PAGE / 2**20
    except OSError:  # not Linux: the peak instead of the current size
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def rss_anon_mib() -> float:
    """Anonymous resident memory (heap, arenas, buffers): what a leak grows, unlike the pages
    of a memory-mapped model file, which come and go with use and memory pressure."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("RssAnon:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return 0.0


def open_fds() -> int:
    try:
        return len(os.listdir("/proc/self/fd"))
    except OSError:
        return -1


def tracked_objects() -> int:
    """How many objects the gc tracks, without holding them: `len(gc.get_objects())` keeps a
    reference to each while another thread may switch in, and a tuple being built from a
    generator there fails with "SystemError: bad argument to internal function" (CPython
    gh-39117; the soak's speech thread, in a full test run here). Freezing moves every tracked
    object to the permanent generation and counts it in C; after a full collection all of them
    are in the oldest generation, where unfreezing puts them back."""
    gc.freeze()
    try:
        return gc.get_freeze_count()
    finally:
        gc.unfreeze()


def take_sample(sim_s: float, wall_s: float) -> Sample:
    """Collect garbage first so the counts are what is alive, then look."""
    gc.collect()
    counts = gc.get_count()
    return Sample(round(sim_s, 1), round(wall_s, 1), round(rss_mib(), 2), sys.getallocatedblocks(),
                  tracked_objects(), (counts[0], counts[1], counts[2]), open_fds(), threading.active_count(),
                  len(asyncio.all_tasks()), round(rss_anon_mib(), 2))


def growth_per_hour(samples: Sequence[Sample], field: str, warm_up_s: float) -> float | None:
    """Least-squares slope of `field` after warm-up, per simulated hour, as a percentage of its
    mean over the same samples (None with fewer than 3 samples after warm-up)."""
    points = [(s.sim_s, float(getattr(s, field))) for s in samples if s.sim_s >= warm_up_s]
    if len(points) < 3:
        return None
    n = len(points)
    mx = sum(x for x, _ in points) / n
    my = sum(y for _, y in points) / n
    var = sum((x - mx) ** 2 for x, _ in points)
    if var == 0 or my == 0:
        return None
    slope = sum((x - mx) * (y - my) for x, y in points) / var
    return round(100.0 * slope * 3600.0 / my, 3)
