"""ThreadStream: a blocking iterator on a worker thread, consumed from asyncio with deadlines."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor

import pytest

from robovoice.llm.base import DeadlineExceededError, Deadlines
from robovoice.llm.bridge import ThreadStream

FAST = Deadlines(first_token_s=0.2, idle_s=0.2, total_s=5.0)


@pytest.fixture
def executor() -> Iterator[ThreadPoolExecutor]:
    pool = ThreadPoolExecutor(max_workers=1)
    yield pool
    pool.shutdown(wait=True)


async def test_items_arrive_in_order_from_the_worker_thread(executor: ThreadPoolExecutor) -> None:
    threads: set[str] = set()

    def produce(stop: threading.Event) -> Iterator[int]:
        for i in range(5):
            threads.add(threading.current_thread().name)
            yield i

    stream = ThreadStream(executor, produce, deadlines=FAST, where="test")
    assert [i async for i in stream.run()] == [0, 1, 2, 3, 4]
    assert threading.current_thread().name not in threads


async def test_errors_are_raised_in_the_caller(executor: ThreadPoolExecutor) -> None:
    def produce(stop: threading.Event) -> Iterator[int]:
        yield 1
        raise ValueError("model broke")

    got: list[int] = []
    with pytest.raises(ValueError, match="model broke"):
        async for item in ThreadStream(executor, produce, deadlines=FAST, where="test").run():
            got.append(item)
    assert got == [1]


@pytest.mark.parametrize(("before_first", "deadline"), [(True, "first_token"), (False, "idle")])
async def test_a_stalled_worker_hits_a_deadline_and_is_stopped(
    executor: ThreadPoolExecutor, before_first: bool, deadline: str
) -> None:
    release = threading.Event()
    stopped = threading.Event()

    def produce(stop: threading.Event) -> Iterator[int]:
        try:
            if not before_first:
                yield 1
            release.wait(5)  # a long prompt evaluation
            yield 2
            yield 3
        finally:
            stopped.set()

    stream = ThreadStream(executor, produce, deadlines=FAST, where="model X")
    start = time.monotonic()
    with pytest.raises(DeadlineExceededError) as info:
        async for _ in stream.run():
            pass
    assert info.value.deadline == deadline and "model X" in str(info.value)
    assert time.monotonic() - start < 1.0
    release.set()
    assert stream.pending is not None
    await stream.pending  # the owner waits for the worker: it stops after the blocking call
    assert stopped.is_set()


async def test_closing_early_stops_the_worker(executor: ThreadPoolExecutor) -> None:
    produced: list[int] = []

    def produce(stop: threading.Event) -> Iterator[int]:
        for i in range(1000):
            if stop.is_set():
                return
            produced.append(i)
            yield i
            stop.wait(0.001)

    stream = ThreadStream(executor, produce, deadlines=FAST, where="test")
    items = stream.run()
    assert await anext(items) == 0
    await items.aclose()  # type: ignore[attr-defined]  # run() is an async generator, typed as an iterator
    assert stream.pending is not None
    await stream.pending
    assert len(produced) < 1000
