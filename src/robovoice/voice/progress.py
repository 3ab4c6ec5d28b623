"""Short spoken feedback while robot actions run. Pure logic, clock passed in.

What is said comes from the tool's manifest (`voice.say`, docs/manifest.md), filled from the
call's arguments, its progress reports and its result (`robovoice.manifest.voice.fill`: a
phrase with a missing field is not said):

- `start`: said when the tool is called, so the person hears something within a second of a
  long action, long before it ends and the model words the result ("On my way to the kitchen.");
- `progress`: at most one line per `progress_interval_s` ("Still on my way, 4 metres to the
  kitchen."); a tool without a progress phrase has its report's message said as it is. The
  final report ("arrived ...") is not said: the reply says the result.

`success` / `failure` are not the narrator's: they are the assistant's answer when they fill
(`assistant.phrase`, spoken as reply sentences), so the narrator says nothing when a tool
returns — saying them here as well would say them twice.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

from robovoice.manifest.voice import fill
from robovoice.voice.config import SpeechConfig
from robovoice.voice.roles import VoiceRoles

_METRES = re.compile(r"\b(\d+(?:\.\d+)?) m\b")


def _speakable(message: str) -> str:
    def metres(m: re.Match[str]) -> str:
        value = m.group(1)
        return f"{value} metre" if value in ("1", "1.0") else f"{value} metres"

    return _METRES.sub(metres, message.strip().rstrip("."))


def _fields(*parts: Mapping[str, Any] | None) -> dict[str, Any]:
    """Template fields: the parts merged, empty strings left out (a missing field)."""
    merged: dict[str, Any] = {}
    for part in parts:
        for key, value in (part or {}).items():
            if value is not None and value != "":
                merged[key] = value
    return merged


class ProgressNarrator:
    """Decides which action feedback is worth saying, and how. `roles` (the robot's voice
    roles and phrases) is replaced when the tool list changes."""

    def __init__(self, config: SpeechConfig, roles: VoiceRoles | None = None) -> None:
        self.config = config
        self.roles = roles or VoiceRoles()
        self._last_spoken: dict[str, float] = {}

    def reset(self) -> None:
        self._last_spoken.clear()

    def on_call(self, name: str, arguments: Mapping[str, Any], now: float) -> str | None:
        """The acknowledgement of a call (None when the tool declares none)."""
        line = fill(self.roles.say(name).start, _fields(arguments))
        if line is not None:
            self._last_spoken[name] = now
        return line

    def on_progress(
        self, name: str, progress: float, total: float | None, message: str, now: float,
        arguments: Mapping[str, Any] | None = None,
    ) -> str | None:
        """A progress line, or None when throttled, final, or saying nothing."""
        if total is not None and total > 0 and progress >= total:
            return None
        if message.lower().startswith(("arrived", "done", "finished")):
            return None
        last = self._last_spoken.get(name)
        if last is not None and now - last < self.config.progress_interval_s:
            return None
        percent = 100.0 * progress / total if total else None
        template = self.roles.say(name).progress
        if template is not None:
            line = fill(template, _fields(arguments, {"message": _speakable(message), "progress": progress,
                                                      "total": total, "percent": percent}))
        elif message:
            spoken = _speakable(message)
            line = f"{spoken[:1].upper()}{spoken[1:]}."
        else:
            line = f"{round(percent)} percent done." if percent is not None else None
        if line is not None:
            self._last_spoken[name] = now
        return line
