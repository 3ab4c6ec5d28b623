"""Who holds the floor: the one *active* task (a command turn: STT, the assistant, its
speech), the stop checks running beside it, and the turn numbers.

Every task is created in the pipeline's `asyncio.TaskGroup` (`attach`), none is
fire-and-forget. `changed` is set whenever a task ends, so `VoicePipeline.wait_idle` can wait
on it without polling.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Coroutine
from dataclasses import dataclass
from typing import Any, TypeVar

from robovoice.voice.events import Emit, UtteranceIgnored
from robovoice.voice.listener import HeardUtterance

log = logging.getLogger(__name__)

T = TypeVar("T")


@dataclass(slots=True)
class PipelineStats:
    turns: int = 0
    stops: int = 0
    barge_ins: int = 0
    ignored: int = 0
    rejected_wakes: int = 0
    frontend_s: float = 0.0  # wall time in the front end
    frontend_cpu_s: float = 0.0  # CPU time of the front end's thread
    audio_s: float = 0.0


async def report_ignored(
    emit: Emit, stats: PipelineStats, reason: str, utt: HeardUtterance, text: str | None = None
) -> None:
    """Speech that does not become a command: counted, logged, told to the observer."""
    stats.ignored += 1
    log.info("utterance %.2f-%.2f s ignored: %s", utt.start, utt.end, reason)
    await emit(UtteranceIgnored(reason, utt.start, utt.end, text))


class Floor:
    """See the module docstring."""

    def __init__(self) -> None:
        self._group: asyncio.TaskGroup | None = None
        self._active: asyncio.Task[None] | None = None
        self._active_turn: int | None = None
        self._active_onset: float | None = None  # the start of the utterance the active turn answers
        self._checks: set[asyncio.Task[None]] = set()
        self._next_turn = 0
        self.changed = asyncio.Event()

    def attach(self, group: asyncio.TaskGroup | None) -> None:
        """The TaskGroup that owns every task from now on (None: the pipeline stopped)."""
        self._group = group

    @property
    def running(self) -> bool:
        return self._group is not None

    def new_turn(self) -> int:
        self._next_turn += 1
        return self._next_turn

    def spawn(self, coro: Coroutine[Any, Any, T], name: str) -> asyncio.Task[T]:
        """A task in the pipeline's TaskGroup (e.g. a speculative transcription)."""
        if self._group is None:
            coro.close()
            raise RuntimeError("the voice pipeline is not running")
        return self._group.create_task(coro, name=name)

    def take(self, turn: int, coro: Coroutine[Any, Any, None], onset: float | None = None) -> None:
        """Give the floor to `turn` (the task running `coro`, answering the utterance that
        started at `onset`); whoever held it is cancelled."""
        self.cancel_active()
        self._active_turn = turn
        self._active_onset = onset
        self._active = self.spawn(coro, f"voice-turn-{turn}")
        self._active.add_done_callback(lambda _: self.changed.set())

    def check(self, coro: Coroutine[Any, Any, None]) -> None:
        """A stop check, beside whatever holds the floor."""
        task = self.spawn(coro, "voice-stop-check")
        self._checks.add(task)
        task.add_done_callback(self._check_done)

    def _check_done(self, task: asyncio.Task[None]) -> None:
        self._checks.discard(task)
        self.changed.set()

    @property
    def busy(self) -> bool:
        """A command turn is running."""
        return self._active is not None and not self._active.done()

    @property
    def idle(self) -> bool:
        """No command turn and no stop check is running."""
        return not self.busy and not self._checks

    def cancel_active(self, spare: float | None = None) -> int | None:
        """Cancel the task holding the floor (unless it is the caller, or the turn for the
        utterance that started at `spare`); its turn number."""
        task = self._active
        if task is None or task.done() or task is asyncio.current_task():
            return None
        if spare is not None and self._active_onset == spare:
            return None
        task.cancel()
        return self._active_turn

    def cancel_all(self) -> None:
        self.cancel_active()
        for task in list(self._checks):
            task.cancel()
