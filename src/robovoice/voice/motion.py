"""Is the robot moving? Needed to accept a spoken "stop" without the wake word.

The pipeline knows about drives it started itself (motion tools called in a running turn);
`PoseMotionProbe` also asks the robot, through its pose snapshot tool (``get_robot_pose``,
whose value carries ``"moving"``), so a drive started by anyone else counts too. Answers
are cached briefly and every query is bounded: an unanswered probe means "not known to be
moving".
"""

from __future__ import annotations

import asyncio
import json
import logging
import time
from typing import Any, Protocol

log = logging.getLogger(__name__)


class ToolCaller(Protocol):
    async def call(self, name: str, arguments: dict[str, Any], on_progress: Any = None) -> Any: ...


def _moving_flag(body: Any) -> bool | None:
    if isinstance(body, dict):
        if isinstance(body.get("moving"), bool):
            return bool(body["moving"])
        return _moving_flag(body.get("value"))
    return None


class PoseMotionProbe:
    """Asks the robot's pose tool whether it moves (cached for `cache_s`)."""

    def __init__(self, tools: ToolCaller, *, tool: str = "get_robot_pose", cache_s: float = 0.3,
                 timeout_s: float = 1.0) -> None:
        self._tools = tools
        self.tool = tool
        self._cache_s = cache_s
        self._timeout_s = timeout_s
        self._last: tuple[float, bool] | None = None
        self.available = True

    @property
    def cached(self) -> bool:
        """The last answer if recent, else False (for decisions that cannot wait)."""
        if self._last is None or time.monotonic() - self._last[0] > 2.0:
            return False
        return self._last[1]

    async def __call__(self) -> bool:
        if not self.available:
            return False
        now = time.monotonic()
        if self._last is not None and now - self._last[0] <= self._cache_s:
            return self._last[1]
        try:
            async with asyncio.timeout(self._timeout_s):
                outcome = await self._tools.call(self.tool, {})
        except TimeoutError:
            log.warning("motion probe %s did not answer within %.1f s", self.tool, self._timeout_s)
            return False
        if getattr(outcome, "is_error", False):
            log.info("motion probe %s failed (%s); relying on the pipeline's own drives", self.tool,
                     getattr(outcome, "text", ""))
            self.available = False
            return False
        body = getattr(outcome, "structured", None)
        if body is None:
            try:
                body = json.loads(getattr(outcome, "text", ""))
            except json.JSONDecodeError:
                body = None
        moving = _moving_flag(body)
        if moving is None:
            log.info("motion probe %s gives no 'moving' flag; relying on the pipeline's own drives", self.tool)
            self.available = False
            return False
        self._last = (time.monotonic(), moving)
        return moving
