"""The one place where blocking model inference meets asyncio.

`ThreadStream` runs a blocking iterator (a llama.cpp token stream) on a
model's own single-thread executor and hands its items to async code through a
queue fed with ``loop.call_soon_threadsafe``. Waits are bounded (first item,
gap between items, total) and a deadline raises `DeadlineExceededError`.

Closing early (barge-in, deadline, error) sets a stop flag the worker checks
between items. The worker may still be inside one blocking call (a prompt
evaluation): its future is kept by `ThreadStream.pending` so the owner can
await it before the next job (the executor runs jobs one at a time anyway);
nothing is left running unowned.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections.abc import AsyncIterator, Callable, Iterator
from concurrent.futures import Executor
from dataclasses import dataclass
from typing import Generic, TypeVar

from robovoice.llm.base import DeadlineExceededError, DeadlineName, Deadlines

log = logging.getLogger(__name__)
T = TypeVar("T")


@dataclass(frozen=True, slots=True)
class _Item(Generic[T]):
    value: T


@dataclass(frozen=True, slots=True)
class _Failed:
    error: BaseException


@dataclass(frozen=True, slots=True)
class _Done:
    pass


_Message = _Item[T] | _Failed | _Done


class ThreadStream(Generic[T]):
    """Async iteration over ``produce()`` run on ``executor``; see the module docstring."""

    def __init__(
        self,
        executor: Executor,
        produce: Callable[[threading.Event], Iterator[T]],
        *,
        deadlines: Deadlines,
        where: str,
    ) -> None:
        self._executor = executor
        self._produce = produce
        self._deadlines = deadlines
        self._where = where
        self._stop = threading.Event()
        self.pending: asyncio.Future[None] | None = None

    def _work(self, loop: asyncio.AbstractEventLoop, queue: asyncio.Queue[_Message[T]]) -> None:
        def put(message: _Message[T]) -> None:
            if not loop.is_closed():
                loop.call_soon_threadsafe(queue.put_nowait, message)

        try:
            iterator = self._produce(self._stop)
            try:
                for value in iterator:
                    if self._stop.is_set():
                        break
                    put(_Item(value))
            finally:
                close = getattr(iterator, "close", None)
                if close is not None:
                    close()
        except Exception as exc:  # handed to the async side, raised there
            put(_Failed(exc))
        else:
            put(_Done())

    async def run(self) -> AsyncIterator[T]:
        """Start the job and yield its items; raises what the job raised, or a deadline."""
        loop = asyncio.get_running_loop()
        queue: asyncio.Queue[_Message[T]] = asyncio.Queue()
        d = self._deadlines
        start = time.monotonic()
        total_at = start + d.total_s
        self.pending = loop.run_in_executor(self._executor, self._work, loop, queue)
        phase: DeadlineName = "first_token"
        phase_s, phase_at = d.first_token_s, start + d.first_token_s
        try:
            while True:
                at = min(phase_at, total_at)
                try:
                    async with asyncio.timeout(max(0.0, at - time.monotonic())):
                        message = await queue.get()
                except TimeoutError as exc:
                    if total_at <= phase_at:
                        raise DeadlineExceededError("total", d.total_s, self._where) from exc
                    raise DeadlineExceededError(phase, phase_s, self._where) from exc
                match message:
                    case _Item(value=value):
                        yield value
                        phase, phase_s, phase_at = "idle", d.idle_s, time.monotonic() + d.idle_s
                    case _Failed(error=error):
                        raise error
                    case _Done():
                        return
        finally:
            self._stop.set()
            if self.pending.done():
                await self.pending
