"""Evaluation cases (DESIGN.md §6): JSON Lines, one case per line, paths relative to the file."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from robovoice.errors import ConfigError

SETUP_STATES = ("driving", "in_call", "projector_on")


class ExpectedCall(BaseModel):
    """A tool call that must appear; `args` is a subset match (a list gives alternatives)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    tool: str
    args: dict[str, Any] = Field(default_factory=dict)


class Case(BaseModel):
    """One evaluation case. Unknown fields (`note`, metadata) are kept and ignored."""

    model_config = ConfigDict(extra="allow", frozen=True, populate_by_name=True)

    id: str
    text: str | None = None
    audio: Path | None = None
    wake: bool | None = None
    expect: tuple[ExpectedCall, ...] = ()
    expect_any: tuple[tuple[ExpectedCall, ...], ...] = ()
    forbid: tuple[str, ...] = ()
    setup: str | None = None
    # what kind of request this is (`compound`, `negated`, `mention`…); reports break figures down by it
    case_class: str | None = Field(default=None, alias="class")

    @model_validator(mode="after")
    def _one_input(self) -> Case:
        if (self.text is None) == (self.audio is None):
            raise ValueError("give exactly one of 'text' or 'audio'")
        for state in self.setup_states:
            if state not in SETUP_STATES:
                raise ValueError(f"unknown setup {state!r}; known: {', '.join(SETUP_STATES)} (combine with '+')")
        return self

    @property
    def setup_states(self) -> tuple[str, ...]:
        return tuple(s.strip() for s in self.setup.split("+")) if self.setup else ()

    @property
    def candidates(self) -> tuple[tuple[ExpectedCall, ...], ...]:
        return (self.expect, *self.expect_any)


def load_cases(path: Path) -> list[Case]:
    """Read a case file; audio paths become absolute. Raises ConfigError naming file and line."""
    cases: list[Case] = []
    seen: set[str] = set()
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except OSError as exc:
        raise ConfigError(f"cannot read case file {path}: {exc.strerror}") from exc
    for number, line in enumerate(lines, start=1):
        if not line.strip() or line.lstrip().startswith("//"):
            continue
        try:
            case = Case.model_validate(json.loads(line))
        except json.JSONDecodeError as exc:
            raise ConfigError(f"{path}:{number}: not valid JSON: {exc.msg} at column {exc.colno}") from exc
        except ValidationError as exc:
            problems = "; ".join(
                f"{'.'.join(str(p) for p in e['loc']) or 'case'}: {e['msg']}" for e in exc.errors()
            )
            raise ConfigError(f"{path}:{number}: {problems}") from exc
        if case.id in seen:
            raise ConfigError(f"{path}:{number}: duplicate case id {case.id!r}")
        seen.add(case.id)
        if case.audio is not None:
            audio = case.audio if case.audio.is_absolute() else (path.parent / case.audio)
            case = case.model_copy(update={"audio": audio.resolve()})
        cases.append(case)
    if not cases:
        raise ConfigError(f"{path}: no cases")
    return cases
