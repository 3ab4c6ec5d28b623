"""Typed facts of the voice pipeline, for observers (the live transcript, tests, the demo).

Data events say what was heard or said; `BargedIn` and `StopHeard` are the control facts
(the pipeline has already dropped queued speech and cancelled the turn when they are
emitted). The assistant's own events (`robovoice.assistant.events`: tool calls, results,
progress, sentences) reach the same observer, so one `match` handles both.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Mapping
from dataclasses import dataclass, field
from typing import Literal

from robovoice.assistant.events import TurnEvent
from robovoice.assistant.loop import TurnResult


@dataclass(frozen=True, slots=True)
class WakeWordHeard:
    """The wake phrase was heard at stream time `at` (s); `during_playback` when the robot
    (or a call's remote participant) was speaking at the time. Not `sure`: a score under the
    wake threshold, which wakes the robot only if the transcript names it."""

    score: float
    at: float
    during_playback: bool = False
    sure: bool = True


@dataclass(frozen=True, slots=True)
class WakeWordRejected:
    """A wake detection that was the robot's own playback (what the echo canceller left)."""

    score: float
    at: float


@dataclass(frozen=True, slots=True)
class UtteranceIgnored:
    """Speech that did not become a command, and why (`no_wake_word`, `own_voice`,
    `not_a_stop`, `stopped_at_pause`, `empty`, `wake_only_timeout`)."""

    reason: str
    start: float
    end: float
    text: str | None = None


@dataclass(frozen=True, slots=True)
class TranscriptReady:
    """Speech-to-text of a command (wake phrase removed); `inference_ms` the model time."""

    text: str
    inference_ms: float


@dataclass(frozen=True, slots=True)
class VoiceTurnStarted:
    """A command goes to the model: `text` for the transcribed path, or `audio_s` seconds of
    audio for an audio-capable backend (`text` is then empty)."""

    turn: int
    mode: Literal["text", "audio"]
    text: str
    audio_s: float
    follow_up: bool = False


@dataclass(frozen=True, slots=True)
class VoiceTurnFinished:
    """A turn ended and its speech has been played (or dropped, when `cancelled`).
    `latency_ms`: the turn's stage marks, from end of speech."""

    turn: int
    result: TurnResult | None
    cancelled: bool
    latency_ms: Mapping[str, float] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class SentenceSpoken:
    """Audio for `text` went to the speaker (`kind`: reply, progress, stop, notice)."""

    turn: int | None
    text: str
    kind: str
    duration_s: float


@dataclass(frozen=True, slots=True)
class BargedIn:
    """Control: the wake word came while the robot was speaking or busy; its speech was
    dropped and the running turn cancelled."""

    at: float
    cancelled_turn: int | None


@dataclass(frozen=True, slots=True)
class StopHeard:
    """Control: a spoken stop; the robot's stop tool (`tool`, the manifest's ``stop`` role;
    None when the robot declares none) is called directly, no model."""

    text: str
    at: float
    cancelled_turn: int | None
    tool: str | None = None


@dataclass(frozen=True, slots=True)
class RobotStopped:
    """The stop tool answered (`ok` false: it reported an error, in `detail`); `latency_ms`
    from the end-of-turn decision, `from_last_word_ms` from the user's last word (when the
    pipeline knows the clock of its stream) to the stop tool's answer."""

    ok: bool
    detail: str
    latency_ms: float
    from_last_word_ms: float | None = None


VoiceEvent = (
    WakeWordHeard | WakeWordRejected | UtteranceIgnored | TranscriptReady | VoiceTurnStarted | VoiceTurnFinished
    | SentenceSpoken | BargedIn | StopHeard | RobotStopped
)
PipelineEvent = VoiceEvent | TurnEvent
VoiceObserver = Callable[[PipelineEvent], Awaitable[None] | None]
Emit = Callable[[PipelineEvent], Awaitable[None]]  # the pipeline's own: the observer, awaited
