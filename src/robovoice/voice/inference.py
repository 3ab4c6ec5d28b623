"""The one place where the voice pipeline's blocking model inference meets asyncio.

Every model (wake word + VAD + echo canceller as one "front end", speech-to-text,
text-to-speech) gets its own worker thread: a model never runs two calls at once,
models run in parallel with each other and with the event loop (onnxruntime releases the
GIL), and a slow model (STT) cannot delay another (the front end keeps up with the mic).

Calls wait their turn in order, except an urgent one (`run_first`: a spoken stop's check),
which goes before every call still waiting: on a loaded machine a stop was heard seconds
late behind transcriptions of television (the soak, docs/robustness.md). A call already
running is never interrupted.

If the awaiting task is cancelled (barge-in, stop) before its call starts, the call is
skipped; a call already running on the thread finishes there and its result is dropped.
`aclose()` waits for the calls queued before it, so nothing is left running unowned.
"""

from __future__ import annotations

import asyncio
import itertools
import logging
import queue
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ParamSpec, TypeVar

log = logging.getLogger(__name__)

P = ParamSpec("P")
T = TypeVar("T")

_URGENT, _NORMAL, _LAST = 0, 1, 2


@dataclass(order=True)
class _Job:
    priority: int
    seq: int
    call: Callable[[], Any] | None = field(compare=False)
    future: asyncio.Future[Any] | None = field(compare=False, default=None)


class ModelExecutor:
    """Runs blocking calls of one model on its own thread; `busy_s` adds up their time."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.busy_s = 0.0
        self.calls = 0
        self._jobs: queue.PriorityQueue[_Job] = queue.PriorityQueue()
        self._seq = itertools.count()
        self._closed = False
        self._thread: threading.Thread | None = None  # started by the first call

    async def run(self, fn: Callable[P, T], *args: P.args, **kwargs: P.kwargs) -> T:
        """`fn(*args, **kwargs)` on the model's thread, after the calls already waiting."""
        return await self._submit(_NORMAL, lambda: fn(*args, **kwargs))

    async def run_first(self, fn: Callable[P, T], *args: P.args, **kwargs: P.kwargs) -> T:
        """`fn(*args, **kwargs)` on the model's thread, before the calls still waiting."""
        return await self._submit(_URGENT, lambda: fn(*args, **kwargs))

    async def _submit(self, priority: int, call: Callable[[], T]) -> T:
        if self._closed:
            raise RuntimeError(f"model executor {self.name} is closed")
        if self._thread is None:
            self._thread = threading.Thread(target=self._work, name=f"voice-{self.name}", daemon=True)
            self._thread.start()
        future: asyncio.Future[T] = asyncio.get_running_loop().create_future()
        self._jobs.put(_Job(priority, next(self._seq), call, future))
        return await future

    def _work(self) -> None:
        while True:
            job = self._jobs.get()
            if job.call is None or job.future is None:
                return  # closed
            future = job.future
            if future.done():  # its caller was cancelled while it waited
                continue
            start = time.perf_counter()
            try:
                value, error = job.call(), None
            except BaseException as exc:  # handed to the caller, raised there
                value, error = None, exc
            took = time.perf_counter() - start
            future.get_loop().call_soon_threadsafe(self._settle, future, value, error, took)

    def _settle(self, future: asyncio.Future[Any], value: Any, error: BaseException | None, took: float) -> None:
        self.busy_s += took
        self.calls += 1
        if future.done():
            return
        if error is not None:
            future.set_exception(error)
        else:
            future.set_result(value)

    async def aclose(self) -> None:
        if self._closed:
            return
        self._closed = True
        if self._thread is not None:
            self._jobs.put(_Job(_LAST, next(self._seq), None))
            await asyncio.to_thread(self._thread.join)
        log.debug("model executor %s closed after %d calls (%.2f s busy)", self.name, self.calls, self.busy_s)
