"""Typed facts a conversation turn produces, for observers (the chat printout, the voice
pipeline, the evaluation) — handled with `match`."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True, slots=True)
class TurnStarted:
    text: str


@dataclass(frozen=True, slots=True)
class FirstTokenReceived:
    backend: str


@dataclass(frozen=True, slots=True)
class ToolCalled:
    call_id: str
    name: str
    arguments: dict[str, Any]


@dataclass(frozen=True, slots=True)
class ToolReturned:
    call_id: str
    name: str
    text: str
    is_error: bool
    duration_ms: float


@dataclass(frozen=True, slots=True)
class ToolProgressed:
    name: str
    progress: float
    total: float | None
    message: str


@dataclass(frozen=True, slots=True)
class SentenceReady:
    text: str


@dataclass(frozen=True, slots=True)
class BackendFailed:
    """No LLM backend answered; the assistant speaks `fallback` instead."""

    reason: str
    fallback: str


@dataclass(frozen=True, slots=True)
class TurnFinished:
    reply: str
    calls: tuple[ToolCalled, ...] = field(default_factory=tuple)
    steps: int = 0


TurnEvent = (
    TurnStarted | FirstTokenReceived | ToolCalled | ToolReturned | ToolProgressed | SentenceReady
    | BackendFailed | TurnFinished
)
