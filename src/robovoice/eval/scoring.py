"""Scoring a case against the tool calls that reached the robot (DESIGN.md §6).

`expect` lists calls that must appear in this order among the calls made (others may come
in between); `args` is a subset match where strings compare case-insensitively after
trimming and a list gives acceptable alternatives. An argument matches when either the
value the model sent or the value the robot resolved it to matches ("lounge" that the
robot took as "living room" is a drive to the living room). The case passes when any
candidate (`expect` or one of `expect_any`) matches and no `forbid`den tool ran.

What reached the robot is told apart from what the model asked for: a call the robot
refused before acting (`unknown_target`, `invalid_arguments`, …) moved nothing, so only a
forbidden *actuation* tool that ran counts as a false actuation.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from robovoice.assistant.gate import NOT_REQUESTED
from robovoice.eval.cases import Case, ExpectedCall

# Errors a call can end with after the robot started acting on it: it may have moved.
ACTED_ERRORS = frozenset({"cancelled", "timeout", "battery_empty"})


@dataclass(frozen=True, slots=True)
class MadeCall:
    """A tool call the assistant made, as it reached the robot.

    `error`: the structured error code it ended with (None: success); `resolved`: arguments
    the robot reports it took differently ({"target": "living room"} for "lounge");
    `actuation`: the tool changes the world (not declared read-only)."""

    tool: str
    args: Mapping[str, Any]
    error: str | None = None
    resolved: Mapping[str, Any] = field(default_factory=dict)
    actuation: bool = True

    @property
    def acted(self) -> bool:
        """The robot ran it: success, or an error that comes after acting began."""
        return self.error is None or self.error in ACTED_ERRORS


@dataclass(frozen=True, slots=True)
class Verdict:
    passed: bool
    reason: str
    false_actuations: tuple[str, ...] = ()


def _value_matches(expected: Any, actual: Any) -> bool:
    if isinstance(expected, list):
        return any(_value_matches(option, actual) for option in expected)
    if isinstance(expected, str) and isinstance(actual, str):
        return expected.strip().casefold() == actual.strip().casefold()
    if isinstance(expected, bool) or isinstance(actual, bool):
        return expected is actual
    return bool(expected == actual)


def _arg_matches(key: str, expected: Any, call: MadeCall) -> bool:
    sent = key in call.args and _value_matches(expected, call.args[key])
    return sent or (key in call.resolved and _value_matches(expected, call.resolved[key]))


def call_matches(expected: ExpectedCall, call: MadeCall) -> bool:
    if expected.tool != call.tool:
        return False
    return all(_arg_matches(key, value, call) for key, value in expected.args.items())


def sequence_matches(expected: Sequence[ExpectedCall], calls: Sequence[MadeCall]) -> bool:
    """True when `expected` appears in order within `calls` (a subsequence match)."""
    position = 0
    for call in calls:
        if position < len(expected) and call_matches(expected[position], call):
            position += 1
    return position == len(expected)


def _describe(call: MadeCall) -> str:
    outcome = "" if call.error is None else f" -> {call.error}"
    return f"{call.tool}({dict(call.args)}){outcome}"


def score_case(case: Case, calls: Sequence[MadeCall]) -> Verdict:
    """Pass or fail, judged on what reached the robot: a forbidden tool fails the case when the
    robot ran it; one the robot refused before acting moved nothing and is only noted."""
    ran = [c for c in calls if c.tool in case.forbid and c.acted]
    refused = [c for c in calls if c.tool in case.forbid and not c.acted]
    note = f" (refused by the robot, nothing moved: {', '.join(map(_describe, refused))})" if refused else ""
    if ran:
        actuations = tuple(c.tool for c in ran if c.actuation)
        return Verdict(False, f"called forbidden tool(s): {', '.join(map(_describe, ran))}{note}", actuations)
    # a call the check before acting refused (assistant/gate.py) never reached the robot: it
    # neither fails a case as a forbidden call nor passes one as an expected call
    sent = [c for c in calls if c.error != NOT_REQUESTED]
    for candidate in case.candidates:
        if sequence_matches(candidate, sent):
            return Verdict(True, f"ok{note}")
    wanted = " then ".join(f"{e.tool}({e.args or ''})" for e in case.expect) or "no tool call"
    made = ", ".join(_describe(c) for c in calls) or "none"
    return Verdict(False, f"expected {wanted}; made {made}")


def resolved_arguments(arguments: Mapping[str, Any], result: Mapping[str, Any] | None) -> dict[str, Any]:
    """The arguments the robot reports it resolved to other values: the same key in the
    result (or in an error's `details`) holding a different string ("lounge" → "living room")."""
    if not result:
        return {}
    details = result.get("details")
    sources = [result, details] if isinstance(details, Mapping) else [result]
    out: dict[str, Any] = {}
    for key, sent in arguments.items():
        for source in sources:
            value = source.get(key)
            if isinstance(value, str) and isinstance(sent, str) and not _value_matches(sent, value):
                out[key] = value
                break
    return out
