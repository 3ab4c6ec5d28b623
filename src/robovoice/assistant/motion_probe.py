"""Does the robot move? One bounded question to its pose snapshot tool (the ``pose`` voice
role: its value carries ``"moving"``). The voice pipeline's `MotionWatch` asks it to accept a
spoken "stop" without the wake word; the tool loop asks it before refusing a stop nobody
asked for (`loop.Assistant`)."""

from __future__ import annotations

import asyncio
import json
import logging
from typing import Any

from robovoice.assistant.robot_tools import Toolbox

log = logging.getLogger(__name__)


def _moving_flag(body: Any) -> bool | None:
    if isinstance(body, dict):
        if isinstance(body.get("moving"), bool):
            return bool(body["moving"])
        return _moving_flag(body.get("value"))
    return None


class PoseMotionProbe:
    """Asks the robot's pose tool `tool` whether it moves (one bounded MCP call per query).
    After an error or an answer without a ``moving`` flag it stops asking (`available`)."""

    def __init__(self, tools: Toolbox, tool: str, *, timeout_s: float = 1.0) -> None:
        self._tools = tools
        self.tool = tool
        self._timeout_s = timeout_s
        self.available = True

    async def __call__(self) -> bool | None:
        """True/False, or None when not known (no answer in time, or no usable answer)."""
        if not self.available:
            return None
        try:
            async with asyncio.timeout(self._timeout_s):
                outcome = await self._tools.call(self.tool, {})
        except TimeoutError:
            log.warning("motion probe %s did not answer within %.1f s", self.tool, self._timeout_s)
            return None
        if outcome.is_error:
            log.info("motion probe %s failed (%s); relying on the pipeline's own drives", self.tool, outcome.text)
            self.available = False
            return None
        body = outcome.structured
        if body is None:
            try:
                body = json.loads(outcome.text)
            except json.JSONDecodeError:
                body = None
        moving = _moving_flag(body)
        if moving is None:
            log.info("motion probe %s gives no 'moving' flag; relying on the pipeline's own drives", self.tool)
            self.available = False
        return moving
