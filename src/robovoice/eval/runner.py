"""Run evaluation cases through the assistant and report scores and latencies (DESIGN.md §6).

Every case gets a fresh robot (so one case's drive cannot leak into the next) and a fresh
conversation; the LLM backend is shared, since loading it is the expensive part.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Awaitable, Callable, Mapping, Sequence
from contextlib import AbstractAsyncContextManager
from dataclasses import dataclass, field
from typing import Any, Protocol

from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.assistant.metrics import TurnMetrics, percentile, summarise
from robovoice.assistant.robot_tools import RobotTools
from robovoice.eval.cases import Case
from robovoice.eval.scoring import MadeCall, resolved_arguments, score_case
from robovoice.llm.base import LLMBackend

log = logging.getLogger(__name__)

# The headline latency of a turn: input in (the end-of-turn decision, or text) → first sentence out.
HEADLINE_STAGE = "first_sentence"
# Audio cases also report every stage from the user's last word (issue 12), this one first.
SPEECH_END_STAGE = "first_audio"


class CaseRobot(Protocol):
    """A connected robot for one case (e.g. `assistant.connect.RobotConnection`): its MCP
    tools, and the sim for `setup`."""

    @property
    def tools(self) -> RobotTools: ...

    async def apply_setup(self, setup: str) -> None: ...


@dataclass(frozen=True, slots=True)
class ClipOutcome:
    """What one audio clip led to in the voice pipeline: the turns it ran (none when the
    assistant rightly did nothing, e.g. no wake word; a spoken stop is a turn with the stop
    call) and what was heard on the way."""

    turns: tuple[TurnResult, ...]
    wake_words: int = 0
    transcripts: tuple[str, ...] = ()
    ignored: tuple[str, ...] = ()
    stops: int = 0

    def details(self) -> dict[str, Any]:
        return {"wake_words": self.wake_words, "transcripts": list(self.transcripts),
                "ignored": list(self.ignored), "stops": self.stops}


class ClipRunner(Protocol):
    """The voice pipeline as the evaluation sees it: a clip in, one frozen outcome out."""

    async def run_clip(self, case: Case, backend: LLMBackend, tools: RobotTools) -> ClipOutcome: ...


OpenRobot = Callable[[], AbstractAsyncContextManager[CaseRobot]]


@dataclass
class CaseResult:
    id: str
    passed: bool
    reason: str
    calls: list[dict[str, Any]]
    reply: str
    latency_ms: dict[str, float]
    false_actuations: list[str] = field(default_factory=list)
    extra: dict[str, Any] = field(default_factory=dict)
    case_class: str | None = None  # the case's `class` field, for the per-class figures
    # audio cases: the stages in ms from the user's last word (`TurnMetrics.from_speech_end`)
    from_speech_end_ms: dict[str, float] = field(default_factory=dict)
    # turns no model answered (a missed deadline, a dead server): their outcome says nothing
    # about judgement, so a figure counts only when this is 0 everywhere
    model_unanswered: int = 0

    def to_dict(self) -> dict[str, Any]:
        out = {"id": self.id, "passed": self.passed, "reason": self.reason, "calls": self.calls,
               "false_actuations": self.false_actuations, "reply": self.reply, "latency_ms": self.latency_ms,
               "model_unanswered": self.model_unanswered}
        if self.from_speech_end_ms:
            out["latency_from_speech_end_ms"] = self.from_speech_end_ms
        out.update(self.extra)
        return out


@dataclass
class EvalReport:
    results: list[CaseResult]
    backend: str
    wall_s: float

    def by_class(self) -> dict[str, dict[str, Any]]:
        """Cases, passes and false actuations per case `class` (a case file's own field)."""
        out: dict[str, dict[str, Any]] = {}
        for r in self.results:
            row = out.setdefault(r.case_class or "-", {"cases": 0, "passed": 0, "false_actuations": 0,
                                                       "model_unanswered": 0})
            row["cases"] += 1
            row["passed"] += int(r.passed)
            row["false_actuations"] += len(r.false_actuations)
            row["model_unanswered"] += r.model_unanswered
        for row in out.values():
            row["accuracy"] = round(row["passed"] / row["cases"], 4)
        return out

    def to_dict(self) -> dict[str, Any]:
        passed = sum(r.passed for r in self.results)
        headline = [r.latency_ms[HEADLINE_STAGE] for r in self.results if HEADLINE_STAGE in r.latency_ms]
        spoken = [r.from_speech_end_ms[SPEECH_END_STAGE] for r in self.results
                  if SPEECH_END_STAGE in r.from_speech_end_ms]
        return {
            "cases": len(self.results),
            "passed": passed,
            "accuracy": round(passed / len(self.results), 4) if self.results else 0.0,
            "false_actuations": sum(len(r.false_actuations) for r in self.results),
            "model_unanswered": sum(r.model_unanswered for r in self.results),
            "p50": round(percentile(headline, 50), 1) if headline else None,
            "p95": round(percentile(headline, 95), 1) if headline else None,
            "latency_stage": HEADLINE_STAGE,
            "stages": summarise(r.latency_ms for r in self.results),  # from the end-of-turn decision (or text)
            "speech_end_to_first_audio": ({"p50": round(percentile(spoken, 50), 1),
                                           "p95": round(percentile(spoken, 95), 1), "n": len(spoken)}
                                          if spoken else None),
            "stages_from_speech_end": summarise(r.from_speech_end_ms for r in self.results if r.from_speech_end_ms),
            "classes": self.by_class(),
            "backend": self.backend,
            "wall_s": round(self.wall_s, 1),
            "results": [r.to_dict() for r in self.results],
        }


def _made_calls(
    turns: Sequence[TurnResult], read_only: Mapping[str, bool]
) -> list[MadeCall]:
    """The calls of `turns` with what became of them at the robot."""
    made: list[MadeCall] = []
    for turn in turns:
        returned = {o.call_id: o for o in turn.outcomes}
        for call in turn.calls:
            outcome = returned.get(call.call_id)
            error = None if outcome is None else (outcome.error or ("tool_error" if outcome.is_error else None))
            resolved = resolved_arguments(call.arguments, outcome.result if outcome is not None else None)
            made.append(MadeCall(call.name, call.arguments, error, resolved, not read_only.get(call.name, False)))
    return made


async def run_case(
    case: Case, backend: LLMBackend, open_robot: OpenRobot, audio: ClipRunner | None = None
) -> CaseResult:
    details: dict[str, Any] = {}
    async with open_robot() as link:
        if case.setup:
            await link.apply_setup(case.setup)
        # which tools declare themselves read-only (they cannot be false actuations); the list
        # is the one the assistant fetches for its first turn anyway
        read_only = {spec.name: spec.read_only for spec in await link.tools.specs()}
        if case.audio is not None:
            if audio is None:
                return CaseResult(case.id, False, "audio case but no voice pipeline available", [], "", {})
            clip = await audio.run_clip(case, backend, link.tools)
            turns, details = clip.turns, clip.details()
        else:
            assert case.text is not None
            turns = (await Assistant(backend, link.tools).turn(case.text, metrics=TurnMetrics()),)
    calls = _made_calls(turns, read_only)
    verdict = score_case(case, calls)
    return CaseResult(
        id=case.id,
        passed=verdict.passed,
        reason=verdict.reason,
        calls=[{"tool": c.tool, "args": dict(c.args), "error": c.error, "resolved": dict(c.resolved)} for c in calls],
        reply=" ".join(t.reply for t in turns),
        latency_ms=turns[0].metrics.as_dict() if turns else {},
        false_actuations=list(verdict.false_actuations),
        extra=details,
        case_class=case.case_class,
        from_speech_end_ms=turns[0].metrics.from_speech_end() if turns else {},
        model_unanswered=sum(t.fell_back for t in turns),
    )


async def run_eval(
    cases: Sequence[Case],
    backend: LLMBackend,
    open_robot: OpenRobot,
    *,
    audio: ClipRunner | None = None,
    on_result: Callable[[CaseResult], Awaitable[None] | None] | None = None,
) -> EvalReport:
    start = time.perf_counter()
    results: list[CaseResult] = []
    for case in cases:
        result = await run_case(case, backend, open_robot, audio)
        log.info("case %s: %s (%s)", case.id, "pass" if result.passed else "FAIL", result.reason)
        results.append(result)
        if on_result is not None:
            maybe = on_result(result)
            if maybe is not None:
                await maybe
    return EvalReport(results, backend.name, time.perf_counter() - start)


