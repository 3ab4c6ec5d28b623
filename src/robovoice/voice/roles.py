"""The robot's voice roles, from its tool list: which tool a spoken "stop" calls, which tools
move the robot, which snapshot tells whether it moves, and what is said about each tool.

Nothing here knows any robot's tool names: they come from the ``voice`` sections of the
robot's manifests (docs/manifest.md), which reach the assistant in each tool's ``_meta``
(`robovoice.assistant.robot_tools.Toolbox.voice`). `VoiceRoles.from_tools` runs at start-up
and whenever the tool list changes.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from dataclasses import dataclass, field

from robovoice.manifest.voice import VoiceDecl, VoicePhrases, tools_with_role

log = logging.getLogger(__name__)

NO_PHRASES = VoicePhrases()


@dataclass(frozen=True, slots=True)
class VoiceRoles:
    """`stop`: the tool a spoken stop calls directly (None: the robot declares none, a spoken
    stop then cannot reach it without the model); `motion`: tools during which the robot
    moves; `pose`: the snapshot whose value says whether the robot moves; `phrases`: what
    is said about each tool, by name."""

    stop: str | None = None
    motion: frozenset[str] = frozenset()
    pose: str | None = None
    phrases: Mapping[str, VoicePhrases] = field(default_factory=dict)

    @classmethod
    def from_tools(cls, sections: Mapping[str, VoiceDecl]) -> VoiceRoles:
        """The roles declared in the tools' voice sections (the first of a role, by name,
        where a robot declares more than one stop or pose tool)."""
        stops = tools_with_role(sections, "stop")
        poses = tools_with_role(sections, "pose")
        if len(stops) > 1:
            log.warning("tools %s all declare the voice role 'stop'; a spoken stop calls %s", stops, stops[0])
        return cls(
            stop=stops[0] if stops else None,
            motion=frozenset(tools_with_role(sections, "motion")),
            pose=poses[0] if poses else None,
            phrases={name: s.say for name, s in sections.items()},
        )

    def say(self, tool: str) -> VoicePhrases:
        """The phrases declared for `tool` (none when it declares none)."""
        return self.phrases.get(tool, NO_PHRASES)

    def describe(self) -> str:
        motion = ", ".join(sorted(self.motion)) or "none"
        return f"stop: {self.stop or 'NONE'}; motion: {motion}; pose: {self.pose or 'none'}"


NO_STOP_WARNING = (
    "the robot declares no stop tool (a tool with \"voice\": {\"role\": \"stop\"} in its manifest): "
    "a spoken \"stop\" cannot stop it without the language model"
)
