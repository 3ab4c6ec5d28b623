"""Measure a direct path: the steps the reading finds, each resolved to one call without the model.

The reading (`assistant/intent.py`) splits a request into steps, and the check before acting
(`assistant/gate.py`, `assistant/fit.py`) knows which tool a step's words fit and which listed
value it names. Where every step of an utterance fits exactly one of the sim robot's actuation
calls, the turn could run them in order with no model step. This measures, on the text cases of
evaluation files and with no model, how many cases such a path would take, and how those would
score: right, wrong, false actuations (the robot's own refusals simulated from the case's
`setup`: no cancel or end of a call when there is nothing to cancel or end).

    .venv/bin/python scripts/measure_direct.py tests/data/eval/text.jsonl [more files] [--show wrong]
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from collections import Counter
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from reading_diff import CALLS, _sim_tools

from robovoice.assistant.fit import fits, unsaid
from robovoice.assistant.gate import refusal
from robovoice.assistant.intent import read_request
from robovoice.assistant.lexicon import words
from robovoice.assistant.reading import Clause, ClauseKind, Intent
from robovoice.eval.cases import load_cases
from robovoice.eval.scoring import MadeCall, score_case

SPECS, VOICE = _sim_tools()
NAMED = ("navigate_to", "start_video_call")


def step_calls(intent: Intent, index: int, worded: str) -> list[tuple[str, dict[str, Any]]]:
    """The sim's actuation calls the gate lets through for this one step (the other requests
    read as talk), whose listed value the step itself names, and whose on/off it says."""
    asked = [i for i, c in enumerate(intent.clauses) if c.kind in (ClauseKind.REQUEST, ClauseKind.QUESTION)]
    clauses = tuple(Clause(worded, ClauseKind.REQUEST) if i == asked[index] else
                    Clause(c.text, ClauseKind.STATEMENT) if c.kind in (ClauseKind.REQUEST, ClauseKind.QUESTION) else c
                    for i, c in enumerate(intent.clauses))
    alone = Intent(clauses, intent.answering)
    said = words(worded)
    kept = []
    for name, args in CALLS:
        spec = SPECS[name]
        if refusal(alone, spec, args, (), VOICE, tools=list(SPECS.values())) is not None:
            continue
        if name in NAMED and unsaid(spec.description, spec.parameters, args, said):
            continue
        if (name == "set_projector_power" and ("on" in said) == ("off" in said)) or (
                name == "set_projector_power" and ("on" in said) != args["on"]):
            continue
        kept.append((name, args))
    names = {n for n, _ in kept}
    for name in NAMED:  # the step asks for this tool, but names none of its values: the model's to resolve
        if name not in names and fits(alone, name, VOICE[name].words, {}):
            return []
    if {"return_to_dock", "navigate_to"} == names and kept[[n for n, _ in kept].index("navigate_to")][1] == {
            "target": "charging dock"}:
        kept = [("return_to_dock", {})]
    if {"stop_robot", "cancel_navigation"} <= names and len(names) == 2:
        kept = [("stop_robot", {})]
    return kept


# what a look-up is asked with (the read-only tools declare no words): such a step is the model's
_LOOKS = re.compile(r"\b(?:photo|picture|camera|image|snap|look|see|contacts?|list|battery|charge left|where|which"
                    r"|what)\b", re.IGNORECASE)
HALTS = ("stop_robot", "cancel_navigation")  # the stop and the cancel keep their own rules (halting.halts, the pose)


def direct(text: str) -> list[tuple[str, dict[str, Any]]] | None:
    """The calls of a direct turn, or None when some step does not fit exactly one call."""
    intent = read_request(text)
    if not intent.steps or any(intent.lookups) or "?" in text:
        return None
    if any(_LOOKS.search(step) for step in intent.worded_steps):
        return None
    calls = []
    for k, worded in enumerate(intent.worded_steps):
        kept = step_calls(intent, k, worded)
        if len(kept) != 1 or kept[0][0] in HALTS:
            return None
        calls.append(kept[0])
    return calls


def robot_error(tool: str, setup: str) -> str | None:
    """What the sim would answer before acting, from the case's setup (simulated)."""
    if tool == "cancel_navigation" and "driving" not in setup:
        return "not_driving"
    if tool == "end_video_call" and "in_call" not in setup:
        return "not_in_call"
    return None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", type=Path)
    parser.add_argument("--show", choices=("wrong", "all", "none"), default="wrong")
    ns = parser.parse_args()
    totals: Counter[str] = Counter()
    per_class: dict[str, Counter[str]] = {}
    for path in ns.files:
        for case in load_cases(path):
            if case.text is None:
                continue
            cls = str(case.case_class or "dev")
            counts = per_class.setdefault(cls, Counter())
            counts["cases"] += 1
            totals["cases"] += 1
            calls = direct(case.text)
            if calls is None:
                continue
            made = [MadeCall(t, a, robot_error(t, case.setup or "")) for t, a in calls]
            verdict = score_case(case, made)
            key = "right" if verdict.passed else "wrong"
            for c in (counts, totals):
                c["direct"] += 1
                c[key] += 1
                c["false_actuations"] += len(verdict.false_actuations)
            if ns.show == "all" or (ns.show == "wrong" and not verdict.passed):
                print(json.dumps({"id": case.id, "file": path.stem, key: verdict.reason, "text": case.text}))
    print(f"\n{'class':10} {'cases':>6} {'direct':>7} {'right':>6} {'wrong':>6} {'FA':>4}")
    for cls, c in [*sorted(per_class.items()), ("all", totals)]:
        print(f"{cls:10} {c['cases']:6d} {c['direct']:7d} {c['right']:6d} {c['wrong']:6d} {c['false_actuations']:4d}")


if __name__ == "__main__":
    main()
