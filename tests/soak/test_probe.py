"""The soak's object count is safe beside threads that build tuples from generators."""

from __future__ import annotations

import gc
import threading
import time
from collections.abc import Iterator

from robovoice.soak.probe import tracked_objects


def _rows() -> Iterator[list[int]]:
    for i in range(200):
        yield [i]  # an allocation between yields, as a synthesiser's chunks are


def test_counting_objects_never_breaks_a_tuple_built_in_another_thread() -> None:
    # len(gc.get_objects()) here made tuple(generator) there fail about once a second
    # ("SystemError: bad argument to internal function"), as the soak's speech thread did.
    errors: list[SystemError] = []
    stop = threading.Event()

    def build() -> None:
        while not stop.is_set():
            try:
                tuple(_rows())
            except SystemError as exc:
                errors.append(exc)

    thread = threading.Thread(target=build)
    thread.start()
    counts = []
    try:
        deadline = time.monotonic() + 2.0
        while time.monotonic() < deadline:
            counts.append(tracked_objects())
    finally:
        stop.set()
        thread.join()
    assert errors == []
    assert len(counts) > 10 and min(counts) > 1000  # slower with the whole suite loaded (~50 here)


def test_the_count_is_what_the_gc_tracks_and_leaves_nothing_frozen() -> None:
    gc.collect()
    counted = tracked_objects()
    listed = len(gc.get_objects())
    assert abs(counted - listed) <= 5  # the list and this frame's locals
    assert gc.get_freeze_count() == 0
