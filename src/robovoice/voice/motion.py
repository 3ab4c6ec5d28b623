"""Is the robot moving? Needed to accept a spoken "stop" without the wake word.

`MotionWatch.moving` answers at once, never waiting on the network (it is asked inside the
microphone loop): true while a motion tool (the ``motion`` role) called in a running turn is
under way, or when the robot's own last answer says so. That answer comes from a local
callable (the embedded sim's state), or from `PoseMotionProbe`, which asks the robot's pose
snapshot tool (the ``pose`` role: its value carries ``"moving"``) -- in `MotionWatch.run`, a
task of the pipeline's TaskGroup, refreshed whenever speech starts or pauses (`want`), so a
fresh answer is there by the time the utterance ends. Every query is bounded; a probe that
does not answer means "not known to be moving".
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Callable

from robovoice.assistant.motion_probe import PoseMotionProbe
from robovoice.assistant.robot_tools import Toolbox

log = logging.getLogger(__name__)


class MotionWatch:
    """The pipeline's view of whether the robot moves (see the module docstring).

    `local`: a callable answering at once (the embedded sim's ``state.moving``); without it
    the pose tool is asked in the background (`set_pose_tool`, from the robot's roles).
    `max_age_s`: an answer older than this no longer counts."""

    def __init__(
        self,
        tools: Toolbox,
        local: Callable[[], bool] | None = None,
        *,
        probe_timeout_s: float = 1.0,
        max_age_s: float = 5.0,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self._tools = tools
        self._local = local
        self._probe_timeout_s = probe_timeout_s
        self._max_age_s = max_age_s
        self._clock = clock
        self.probe: PoseMotionProbe | None = None
        self._last: tuple[float, bool] | None = None
        self._own: set[str] = set()  # call ids of motion tools under way in turns
        self._wanted = asyncio.Event()
        self.probes = 0  # pose queries made (for tests and stats)

    def set_pose_tool(self, tool: str | None) -> None:
        """The robot's pose tool (None: it declares none); a new one starts fresh."""
        if self._local is not None or (self.probe is not None and self.probe.tool == tool):
            return
        self.probe = PoseMotionProbe(self._tools, tool, timeout_s=self._probe_timeout_s) if tool else None
        self._last = None

    def started(self, call_id: str) -> None:
        """A motion tool was called in a turn."""
        self._own.add(call_id)

    def finished(self, call_id: str) -> None:
        if call_id in self._own:
            self._last = None  # a "moving" heard while our own drive ran is over with it
        self._own.discard(call_id)

    def forget(self, call_ids: set[str]) -> None:
        self._own.difference_update(call_ids)

    @property
    def own_motion(self) -> bool:
        return bool(self._own)

    def _answer(self) -> bool | None:
        """Whether the robot moves now, without waiting: a drive of ours, the local answer, or the
        pose tool's last answer if recent enough; None when not known."""
        if self._own:
            return True
        if self._local is not None:
            return bool(self._local())
        last = self._last
        return last[1] if last is not None and self._clock() - last[0] <= self._max_age_s else None

    @property
    def moving(self) -> bool:
        """Known to move now (`_answer`)."""
        return self._answer() is True

    @property
    def known_still(self) -> bool:
        """Known not to move now (`_answer`): not known (no probe, no answer yet, an old one) is
        not still."""
        return self._answer() is False

    def want(self) -> None:
        """Ask for a fresh answer from the pose tool (returns at once)."""
        if self.probe is not None and self.probe.available:
            self._wanted.set()

    async def run(self) -> None:
        """Refresh the pose tool's answer whenever one is wanted; until cancelled."""
        while True:
            await self._wanted.wait()
            self._wanted.clear()
            probe = self.probe
            if probe is None:
                continue
            self.probes += 1
            moving = await probe()
            if moving is not None and probe is self.probe:
                self._last = (self._clock(), moving)
