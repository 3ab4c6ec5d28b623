"""Scoring a case against the tool calls the assistant made (DESIGN.md §6).

`expect` lists calls that must appear in this order among the calls made (others may come
in between); `args` is a subset match where strings compare case-insensitively after
trimming and a list gives acceptable alternatives. The case passes when any candidate
(`expect` or one of `expect_any`) matches and no `forbid`den tool was called.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from robovoice.eval.cases import Case, ExpectedCall


@dataclass(frozen=True, slots=True)
class MadeCall:
    """A tool call the assistant made, as recorded for scoring."""

    tool: str
    args: Mapping[str, Any]


@dataclass(frozen=True, slots=True)
class Verdict:
    passed: bool
    reason: str


def _value_matches(expected: Any, actual: Any) -> bool:
    if isinstance(expected, list):
        return any(_value_matches(option, actual) for option in expected)
    if isinstance(expected, str) and isinstance(actual, str):
        return expected.strip().casefold() == actual.strip().casefold()
    if isinstance(expected, bool) or isinstance(actual, bool):
        return expected is actual
    return bool(expected == actual)


def call_matches(expected: ExpectedCall, call: MadeCall) -> bool:
    if expected.tool != call.tool:
        return False
    return all(key in call.args and _value_matches(value, call.args[key]) for key, value in expected.args.items())


def sequence_matches(expected: Sequence[ExpectedCall], calls: Sequence[MadeCall]) -> bool:
    """True when `expected` appears in order within `calls` (a subsequence match)."""
    position = 0
    for call in calls:
        if position < len(expected) and call_matches(expected[position], call):
            position += 1
    return position == len(expected)


def score_case(case: Case, calls: Sequence[MadeCall]) -> Verdict:
    forbidden = [c.tool for c in calls if c.tool in case.forbid]
    if forbidden:
        return Verdict(False, f"called forbidden tool(s): {', '.join(forbidden)}")
    for candidate in case.candidates:
        if sequence_matches(candidate, calls):
            return Verdict(True, "ok")
    wanted = " then ".join(f"{e.tool}({e.args or ''})" for e in case.expect) or "no tool call"
    made = ", ".join(f"{c.tool}({dict(c.args)})" for c in calls) or "none"
    return Verdict(False, f"expected {wanted}; made {made}")
