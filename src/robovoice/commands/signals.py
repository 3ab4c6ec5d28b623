"""Ending a long-running command cleanly on SIGINT / SIGTERM."""

from __future__ import annotations

import asyncio
import signal
from types import TracebackType

SIGNALS = (signal.SIGINT, signal.SIGTERM)


class CancelOnSignals:
    """Within the block, SIGINT or SIGTERM cancels the current task once; the block's
    `CancelledError` caused by it is swallowed so `finally` clean-ups run and the command
    exits 0. `signalled` says whether that happened.

        with CancelOnSignals() as stop:
            try:
                await serve_forever()
            finally:
                await close()
    """

    def __init__(self) -> None:
        self.signalled = False
        self._task: asyncio.Task[object] | None = None
        self._loop: asyncio.AbstractEventLoop | None = None

    def __enter__(self) -> CancelOnSignals:
        self._loop = asyncio.get_running_loop()
        self._task = asyncio.current_task()
        for signum in SIGNALS:
            self._loop.add_signal_handler(signum, self._on_signal)
        return self

    def _on_signal(self) -> None:
        if not self.signalled and self._task is not None:
            self.signalled = True
            self._task.cancel()

    def __exit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> bool:
        assert self._loop is not None
        for signum in SIGNALS:
            self._loop.remove_signal_handler(signum)
        if exc_type is asyncio.CancelledError and self.signalled and self._task is not None:
            self._task.uncancel()
            return True
        return False
