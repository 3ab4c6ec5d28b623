"""Per-turn latency: timestamps of each stage, relative to the turn's start.

The turn starts when the end of turn is decided (voice: the chunk in which the end-of-turn
silence was complete) or when the text arrives (chat). Stages: `endpoint`, `transcript`,
`first_token`, `tool_call:<name>` / `tool_result:<name>`, `first_sentence`, `first_audio`,
`finished`. `model_ms` adds up the time spent waiting for the model, so the rest of a turn
can be reported as our own overhead.

A voice turn also knows `speech_end`, the clock time of the user's last word (the VAD's last
voiced frame, mapped from stream time to the clock: `voice.clock.StreamAnchor`), which comes
before the decision by the end-of-turn silence. `from_speech_end()` gives every stage from that
origin, the one a person feels (issue 12); `as_dict()` keeps the decision as its origin.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field


@dataclass
class TurnMetrics:
    clock: Callable[[], float] = time.perf_counter
    start: float = field(default=0.0)
    marks: dict[str, float] = field(default_factory=dict)
    model_ms: float = 0.0
    tools_ms: float = 0.0
    stt_ms: float = 0.0
    tts_ms: float = 0.0
    speech_end: float | None = None  # clock time of the user's last word (voice turns), see the docstring

    def __post_init__(self) -> None:
        if not self.start:
            self.start = self.clock()

    def mark(self, stage: str, at: float | None = None) -> None:
        """Record the first time `stage` happens (later marks of the same stage are ignored)."""
        if stage not in self.marks:
            self.marks[stage] = ((self.clock() if at is None else at) - self.start) * 1000.0

    def as_dict(self) -> dict[str, float]:
        out = {stage: round(ms, 1) for stage, ms in self.marks.items()}
        out.update(model_ms=round(self.model_ms, 1), tools_ms=round(self.tools_ms, 1))
        if self.stt_ms:
            out["stt_ms"] = round(self.stt_ms, 1)
        if self.tts_ms:
            out["tts_ms"] = round(self.tts_ms, 1)
        return out

    def from_speech_end(self) -> dict[str, float]:
        """The stage marks in ms from the user's last word ({} when it is not known). Here
        `endpoint` is how long after the last word the end of turn was decided."""
        if self.speech_end is None:
            return {}
        shift = (self.start - self.speech_end) * 1000.0
        return {stage: round(ms + shift, 1) for stage, ms in self.marks.items()}


def percentile(values: Sequence[float], q: int) -> float:
    """The q-th percentile (q in 0..100), interpolating linearly between the closest ranks.

    This is `statistics.quantiles(values, n=100, method="inclusive")` (numpy's default
    ``linear`` method), plus the ends: q=0 is the minimum, q=100 the maximum, and one value is
    every percentile of itself.
    """
    if not values:
        raise ValueError("no values")
    if not 0 <= q <= 100:
        raise ValueError(f"percentile must be in 0..100, got {q}")
    if len(values) == 1 or q in (0, 100):
        return float(min(values) if q == 0 else max(values))
    return statistics.quantiles(values, n=100, method="inclusive")[q - 1]


def summarise(per_turn: Iterable[Mapping[str, float]]) -> dict[str, dict[str, float]]:
    """p50/p95 per stage over many turns (stages missing from a turn are skipped)."""
    by_stage: dict[str, list[float]] = {}
    for turn in per_turn:
        for stage, ms in turn.items():
            if stage.startswith(("tool_call:", "tool_result:")):
                stage = stage.split(":", 1)[0]
            by_stage.setdefault(stage, []).append(ms)
    return {
        stage: {"p50": round(percentile(v, 50), 1), "p95": round(percentile(v, 95), 1), "n": len(v)}
        for stage, v in sorted(by_stage.items())
    }
