"""The optional ``voice`` section of a manifest tool: its role for the voice pipeline and
what the robot says while it runs.

    "voice": {
      "role": "motion",
      "say": {"start": "On my way to the {target}.", "progress": "Still on my way, {message}."}
    }

Roles: ``stop`` (the tool a spoken "stop" calls directly, without the model), ``motion``
(while it runs the robot moves, so a short "stop" needs no wake word), ``pose`` (a snapshot
whose value carries ``"moving": true|false``: whether the robot moves, whoever drives it).

Phrases are ``str.format`` templates with plain named fields (``{target}``, ``{percent:.0f}``):
no attribute or index look-ups, no positional fields. A yes/no field picks one of two words
with ``{on:on|off}`` (true: the text before ``|``, false: the text after). They are filled from
the call's arguments (`start`); its progress report's ``message``, ``progress``, ``total`` and
``percent`` (`progress`); the arguments and the top-level fields of the structured result
(`success`), or of the error body ``error``, ``message``, ``hint`` (`failure`): see
`result_fields`; `confirm` (the question asked before a call on words that may have been
misheard) from the arguments. A field that is missing (or a value its format spec does not
fit) gives no phrase at all: `fill` returns None, it never raises. The same section reaches MCP clients in
the tool's ``_meta`` under `META_KEY`, so a remote assistant reads it from ``tools/list``.
"""

from __future__ import annotations

import re
import string
from collections.abc import Mapping
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator

META_KEY = "robovoice/voice"

_FIELD = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_FORMATTER = string.Formatter()

VoiceRole = Literal["stop", "cancel", "motion", "pose"]


def template_fields(template: str) -> list[str]:
    """The field names of a phrase template; `ValueError` for what `fill` does not allow."""
    names: list[str] = []
    for _, name, spec, _ in _FORMATTER.parse(template):
        if name is None:
            continue
        if not _FIELD.match(name):
            raise ValueError(f"{{{name}}} is not a plain field name: write {{name}}, no positions, dots or "
                             "brackets")
        if spec and "{" in spec:
            raise ValueError(f"nested fields in the format spec of {{{name}}} are not allowed")
        names.append(name)
    return names


def fill(template: str | None, fields: Mapping[str, Any]) -> str | None:
    """`template` filled from `fields`; None when a field is missing or does not fit its
    format spec (a phrase that cannot be said completely is not said)."""
    if not template:
        return None
    out: list[str] = []
    try:
        for literal, name, spec, conversion in _FORMATTER.parse(template):
            out.append(literal)
            if name is None:
                continue
            if not _FIELD.match(name) or name not in fields or fields[name] is None:
                return None
            value = fields[name]
            if isinstance(value, bool) and spec and "|" in spec:  # {on:on|off}
                out.append(spec.split("|", 1)[0 if value else 1])
                continue
            if conversion:
                value = _FORMATTER.convert_field(value, conversion)
            out.append(format(value, spec or ""))
    except (ValueError, TypeError):
        return None
    text = "".join(out).strip()
    return text or None


def result_fields(arguments: Mapping[str, Any] | None, result: Mapping[str, Any] | None) -> dict[str, Any]:
    """The fields a `success` / `failure` phrase is filled from: the call's arguments, then the
    plain values (text, numbers, yes/no) of a fresh snapshot's message, then those at the top
    of the structured result (which win). Empty text counts as missing."""
    merged: dict[str, Any] = {}
    result = result or {}
    value = result.get("value")
    # a snapshot tool returns its message under "value"; a stale message fills nothing
    message = value if isinstance(value, Mapping) and result.get("stale") is False else {}
    for part in (arguments or {}, message, result):
        for key, item in part.items():
            if isinstance(item, (str, int, float, bool)) and item != "":
                merged[key] = item
    return merged


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class VoicePhrases(_Strict):
    """What the robot says about the tool (each optional; see the module docstring)."""

    start: str | None = Field(default=None, description="said when the tool is called, e.g. "
                              "\"On my way to the {target}.\" (fields: the arguments); withdrawn when "
                              "the tool fails before it was played")
    progress: str | None = Field(default=None, description="said for a progress report (at most one per "
                                 "progress interval; fields: message, progress, total, percent and the arguments)")
    success: str | None = Field(default=None, description="said when the tool succeeds (fields: the arguments "
                                "and the structured result's top-level fields)")
    failure: str | None = Field(default=None, description="said when the tool fails (fields: the arguments, "
                                "error, message, hint)")
    confirm: str | None = Field(default=None, description="asked before the tool runs when the words it was "
                                "called on may have been misheard, e.g. \"Shall I call {contact}?\" (fields: the "
                                "arguments); it runs on a yes (docs/judgement.md). For tools whose unwanted call "
                                "cannot be taken back")

    @field_validator("start", "progress", "success", "failure", "confirm")
    @classmethod
    def _template(cls, value: str | None) -> str | None:
        if value is not None:
            template_fields(value)
        return value


class VoiceDecl(_Strict):
    """A tool's (or snapshot's) part in the voice pipeline."""

    role: VoiceRole | None = Field(default=None, description="stop: a spoken stop calls it directly; cancel: "
                                   "it calls off what the robot is doing, and may run on \"never mind\" "
                                   "while the robot moves; motion: the robot moves while it runs; pose "
                                   "(snapshots): its value says whether the robot moves (\"moving\": "
                                   "true|false)")
    say: VoicePhrases = Field(default_factory=VoicePhrases, description="phrases spoken about the tool")
    words: tuple[str, ...] = Field(default=(), description="the words (or short phrases) a request for this "
                                   "tool uses besides its name and its arguments' values, e.g. [\"call\", "
                                   "\"ring\", \"phone\"]: a call no request clause fits is refused "
                                   "(docs/judgement.md); none declared: not checked")

    def meta(self) -> dict[str, Any]:
        """The section as it goes into the MCP tool's ``_meta`` (under `META_KEY`)."""
        dumped = self.model_dump(mode="json", exclude_none=True, exclude_defaults=False)
        return {key: value for key, value in dumped.items() if key != "words" or value}


def tools_with_role(sections: Mapping[str, VoiceDecl], role: VoiceRole) -> list[str]:
    """The names of the tools whose voice section declares `role`, sorted (the first is the
    one used where a robot declares more than one stop or pose tool)."""
    return sorted(name for name, section in sections.items() if section.role == role)
