"""Typed facts a conversation turn produces, for observers (the chat printout, the voice
pipeline, the evaluation) — handled with `match`."""

from __future__ import annotations

import inspect
from collections.abc import Awaitable, Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, TypeVar

E = TypeVar("E")


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
    """A tool's result. `error`: the structured error code of a failed call (``unknown_target``,
    ``invalid_arguments``…), None on success; `result`: the structured body the robot sent back
    (the value, or ``{error, message, hint, details}``), None when there was none (an image)."""

    call_id: str
    name: str
    text: str
    is_error: bool
    duration_ms: float
    error: str | None = None
    result: Mapping[str, Any] | None = None


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


async def notify(observer: Callable[[E], Awaitable[None] | None] | None, event: E) -> None:
    """Hand `event` to `observer` (a plain function or a coroutine function), if there is one."""
    if observer is None:
        return
    result = observer(event)
    if inspect.isawaitable(result):
        await result
