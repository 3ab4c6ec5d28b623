"""Run evaluation cases through the assistant and report scores and latencies (DESIGN.md §6).

Every case gets a fresh robot (so one case's drive cannot leak into the next) and a fresh
conversation; the LLM backend is shared, since loading it is the expensive part.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Awaitable, Callable, Sequence
from contextlib import AbstractAsyncContextManager
from dataclasses import dataclass, field
from typing import Any, Protocol

from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.assistant.metrics import TurnMetrics, percentile, summarise
from robovoice.assistant.robot_tools import RobotTools
from robovoice.eval.cases import Case
from robovoice.eval.scoring import MadeCall, score_case
from robovoice.llm.base import LLMBackend

log = logging.getLogger(__name__)

# The headline latency of a turn: input in (end of speech, or text) → first sentence out.
HEADLINE_STAGE = "first_sentence"


class RobotLink(Protocol):
    """A connected robot for one case: its MCP tools, and the sim for `setup`."""

    tools: RobotTools

    async def apply_setup(self, setup: str) -> None: ...


class AudioFrontEnd(Protocol):
    """The voice pipeline as the evaluation sees it: a clip in, the turn it led to (or None
    when the assistant rightly did not act, e.g. no wake word)."""

    async def run_clip(self, case: Case, assistant: Assistant) -> tuple[TurnResult | None, dict[str, Any]]: ...


OpenRobot = Callable[[], AbstractAsyncContextManager[RobotLink]]


@dataclass
class CaseResult:
    id: str
    passed: bool
    reason: str
    calls: list[dict[str, Any]]
    reply: str
    latency_ms: dict[str, float]
    extra: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        out = {"id": self.id, "passed": self.passed, "reason": self.reason, "calls": self.calls,
               "reply": self.reply, "latency_ms": self.latency_ms}
        out.update(self.extra)
        return out


@dataclass
class EvalReport:
    results: list[CaseResult]
    backend: str
    wall_s: float

    def to_dict(self) -> dict[str, Any]:
        passed = sum(r.passed for r in self.results)
        headline = [r.latency_ms[HEADLINE_STAGE] for r in self.results if HEADLINE_STAGE in r.latency_ms]
        return {
            "cases": len(self.results),
            "passed": passed,
            "accuracy": round(passed / len(self.results), 4) if self.results else 0.0,
            "p50": round(percentile(headline, 50), 1) if headline else None,
            "p95": round(percentile(headline, 95), 1) if headline else None,
            "latency_stage": HEADLINE_STAGE,
            "stages": summarise(r.latency_ms for r in self.results),
            "backend": self.backend,
            "wall_s": round(self.wall_s, 1),
            "results": [r.to_dict() for r in self.results],
        }


async def run_case(
    case: Case, backend: LLMBackend, open_robot: OpenRobot, audio: AudioFrontEnd | None = None
) -> CaseResult:
    async with open_robot() as link:
        if case.setup:
            await link.apply_setup(case.setup)
        assistant = Assistant(backend, link.tools)
        extra: dict[str, Any] = {}
        if case.audio is not None:
            if audio is None:
                return CaseResult(case.id, False, "audio case but no voice pipeline available", [], "", {})
            result, extra = await audio.run_clip(case, assistant)
        else:
            assert case.text is not None
            result = await assistant.turn(case.text, metrics=TurnMetrics())
    calls = list(result.calls) if result else []
    verdict = score_case(case, [MadeCall(c.name, c.arguments) for c in calls])
    return CaseResult(
        id=case.id,
        passed=verdict.passed,
        reason=verdict.reason,
        calls=[{"tool": c.name, "args": c.arguments} for c in calls],
        reply=result.reply if result else "",
        latency_ms=result.metrics.as_dict() if result else {},
        extra=extra,
    )


async def run_eval(
    cases: Sequence[Case],
    backend: LLMBackend,
    open_robot: OpenRobot,
    *,
    audio: AudioFrontEnd | None = None,
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


