"""Shared pieces of the fuzzers: bounded, deterministic hypothesis settings; JSON values; an
event loop in a thread, so a synchronous ``@given`` test can drive a real async server."""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Awaitable, Callable, Iterator
from contextlib import AbstractAsyncContextManager, contextmanager
from typing import Any, TypeVar

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

T = TypeVar("T")
CALL_BOUND_S = 15.0  # no single fuzzed request may take longer (a hang fails the test)


def bounded(max_examples: int, deadline_ms: int = 2000) -> settings:
    """Fixed examples, a per-example deadline, derandomized (the same examples on every run: CI is
    deterministic), no example database written."""
    return settings(max_examples=max_examples, deadline=deadline_ms, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                           HealthCheck.function_scoped_fixture])


SCALARS = st.none() | st.booleans() | st.integers(-(2**70), 2**70) | st.floats(allow_nan=False) | st.text(max_size=30)
JSON_VALUES: st.SearchStrategy[Any] = st.recursive(
    SCALARS,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=12), inner, max_size=4),
    max_leaves=12,
)


class LoopThread:
    """An asyncio loop in a daemon thread; `run(coro)` waits for it, bounded by `CALL_BOUND_S`."""

    def __init__(self) -> None:
        self.loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self.loop.run_forever, name="fuzz-loop", daemon=True)
        self._thread.start()

    def run(self, awaitable: Awaitable[T], bound_s: float = CALL_BOUND_S) -> T:
        async def bounded_call() -> T:
            async with asyncio.timeout(bound_s):
                return await awaitable

        return asyncio.run_coroutine_threadsafe(bounded_call(), self.loop).result()

    def close(self) -> None:
        async def cancel_the_rest() -> None:
            rest = [t for t in asyncio.all_tasks() if t is not asyncio.current_task()]
            for task in rest:
                task.cancel()
            await asyncio.gather(*rest, return_exceptions=True)

        asyncio.run_coroutine_threadsafe(cancel_the_rest(), self.loop).result(timeout=10)
        self.loop.call_soon_threadsafe(self.loop.stop)
        self._thread.join(timeout=10)
        self.loop.close()


@contextmanager
def serving(factory: Callable[[], AbstractAsyncContextManager[T]]) -> Iterator[tuple[LoopThread, T]]:
    """Enter the async context `factory()` on a loop thread; yield (loop, what it yields)."""
    loop = LoopThread()
    entered: asyncio.Event | None = None
    leave: asyncio.Event | None = None
    value: list[T] = []

    async def hold() -> None:
        nonlocal entered, leave
        async with factory() as inside:
            value.append(inside)
            assert entered is not None and leave is not None
            entered.set()
            await leave.wait()

    async def start() -> asyncio.Task[None]:
        nonlocal entered, leave
        entered, leave = asyncio.Event(), asyncio.Event()
        task = asyncio.get_running_loop().create_task(hold())
        waiter = asyncio.ensure_future(entered.wait())
        await asyncio.wait({task, waiter}, return_when=asyncio.FIRST_COMPLETED)
        waiter.cancel()
        if task.done():
            task.result()  # raises what went wrong
        return task

    task = loop.run(start(), bound_s=60)
    try:
        yield loop, value[0]
    finally:
        async def stop() -> None:
            assert leave is not None
            leave.set()
            await task

        try:
            loop.run(stop(), bound_s=30)
        finally:
            loop.close()
