"""The one place where the voice pipeline's blocking model inference meets asyncio.

Every model (wake word + VAD + echo canceller as one "front end", speech-to-text,
text-to-speech) gets its own single-thread executor: a model never runs two calls at once,
models run in parallel with each other and with the event loop (onnxruntime releases the
GIL), and a slow model (STT) cannot delay another (the front end keeps up with the mic).

If the awaiting task is cancelled (barge-in, stop) the call already running on the thread
finishes there and its result is dropped; the next call on that model waits behind it.
`aclose()` waits for running calls, so nothing is left running unowned.
"""

from __future__ import annotations

import asyncio
import functools
import logging
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import ParamSpec, TypeVar

log = logging.getLogger(__name__)

P = ParamSpec("P")
T = TypeVar("T")


class ModelExecutor:
    """Runs blocking calls of one model on its own thread; `busy_s` adds up their time."""

    def __init__(self, name: str) -> None:
        self.name = name
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix=f"voice-{name}")
        self.busy_s = 0.0
        self.calls = 0

    async def run(self, fn: Callable[P, T], *args: P.args, **kwargs: P.kwargs) -> T:
        loop = asyncio.get_running_loop()

        def timed() -> tuple[T, float]:
            start = time.perf_counter()
            value = fn(*args, **kwargs)
            return value, time.perf_counter() - start

        value, took = await loop.run_in_executor(self._pool, functools.partial(timed))
        self.busy_s += took
        self.calls += 1
        return value

    async def aclose(self) -> None:
        await asyncio.to_thread(self._pool.shutdown, wait=True)
        log.debug("model executor %s closed after %d calls (%.2f s busy)", self.name, self.calls, self.busy_s)
