"""Short spoken feedback while a long robot action runs. Pure logic, clock passed in.

- When a long tool is called (`SpeechConfig.long_tools`, e.g. a drive) the robot
  acknowledges at once ("On my way to the kitchen."), so the person hears something
  within a second, long before the drive ends and the model words the result.
- Progress reports of the action become at most one short line per
  `progress_interval_s` ("Still on my way, 4 metres to the kitchen."); the final report
  ("arrived ...") is not spoken: the model's reply says the result.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

from robovoice.voice.config import SpeechConfig

_METRES = re.compile(r"\b(\d+(?:\.\d+)?) m\b")


def _speakable(message: str) -> str:
    def metres(m: re.Match[str]) -> str:
        value = m.group(1)
        return f"{value} metre" if value in ("1", "1.0") else f"{value} metres"

    return _METRES.sub(metres, message.strip().rstrip("."))


class ProgressNarrator:
    """Decides which action feedback is worth saying, and how."""

    def __init__(self, config: SpeechConfig | None = None) -> None:
        self.config = config or SpeechConfig()
        self._last_spoken: dict[str, float] = {}

    def reset(self) -> None:
        self._last_spoken.clear()

    def on_call(self, name: str, arguments: Mapping[str, Any], now: float) -> str | None:
        """The acknowledgement for a long tool (None for quick tools)."""
        if name not in self.config.long_tools:
            return None
        self._last_spoken[name] = now
        target = arguments.get("target")
        if name == "return_to_dock" or (isinstance(target, str) and target.strip().lower() == "charging dock"):
            return "Going back to my charging dock."
        if name == "navigate_to" and isinstance(target, str) and target.strip():
            return f"On my way to the {target.strip()}."
        return "One moment, please."

    def on_progress(self, name: str, progress: float, total: float | None, message: str, now: float) -> str | None:
        """A progress line, or None when throttled, final, or saying nothing."""
        if total is not None and total > 0 and progress >= total:
            return None
        if message.lower().startswith(("arrived", "done", "finished")):
            return None
        last = self._last_spoken.get(name)
        if last is not None and now - last < self.config.progress_interval_s:
            return None
        self._last_spoken[name] = now
        if message:
            return f"Still on my way, {_speakable(message)}." if name in ("navigate_to", "return_to_dock") else (
                f"{_speakable(message)[:1].upper()}{_speakable(message)[1:]}."
            )
        if total:
            return f"{round(100 * progress / total)} percent done."
        return None
