"""Words that ask the robot to halt, and words that only say where it is to stay.

The robot's stop and cancel run on halting words even where nothing reads as a request (the loop,
while the robot moves: `loop.Assistant._run_tool`); "wait there" after a drive, or "wait for me in
the kitchen", says where to be and halts nothing.
"""

from __future__ import annotations

import dataclasses
import re

from robovoice.assistant.reading import Clause, ClauseKind, Intent

# Words that may ask the robot to stop or call off what it does although no clause reads as a
# request ("Hold it! Stay put!", "never mind, don't go there after all", "whoa, quit driving"); only with one of them
# does the robot's stop or cancel run on such words ("don't mind the mess in the bedroom",
# said while it drove, cancelled the drive in text test v13)
# (not "hold off on ringing Ben": it puts a call off, no halt; text test v57)
_HALTING = re.compile(r"\b(?:stop\w*|halt|hold(?! off)|stay|wait|hang on|freeze|forget|never ?mind"
                      r"|chang\w* (?:my|your) mind"
                      r"|don'?t (?:bother|go|move|drive)|enough|cancel\w*|call it off|after all|leave it|no further"
                      r"|turn (?:back|round|around)|quit(?:s|ting)?|abort\w*|call (?:(?:the|that|this) \w+ )?off"
                      r"|whoa|scrap (?:it|that|this)|scratch that"  # "scrap that route" (text test v54)
                      r"|belay that|scrub (?:it|that|this)|abandon (?:it|that|this|the)"  # (text test v63)
                      r"|drop (?:that|this|the) (?:trip|drive|journey|run|errand|route))\b",
                      re.IGNORECASE)


# "go to the hallway and wait there", "wait for me in the kitchen": where to be, no halt (the robot's
# stop and cancel ran beside the drive). Alone, "wait there!" may still mean stop where you are: a
# "there" is a place only after a request.
_STAY_AT = re.compile(r"^(?:(?:and|then|so|just|please|now)\b[\s,]*)*(?:wait|stay|hang on|hold on)"
                      r"(?: for (?:me|us|him|her|them))?(?: (?:out|over|down|up|back))?"
                      r"(?: (?P<there>(?:over )?there)\b| (?:in|at|by|near|outside|inside|beside|next to)\b"
                      r"(?! (?:here|me|you)\b))", re.IGNORECASE)


def staying(intent: Intent) -> Intent:
    """The utterance without its clauses that say where to stay (`_STAY_AT`)."""
    def where(i: int, clause: Clause) -> bool:
        found = _STAY_AT.match(clause.text.strip())
        return found is not None and (found["there"] is None or any(
            c.kind is ClauseKind.REQUEST for c in intent.clauses[:i]))
    return dataclasses.replace(intent, clauses=tuple(c for i, c in enumerate(intent.clauses) if not where(i, c)))


def halts(intent: Intent | None) -> bool:
    """The words may ask the robot to stop or call off what it does, and do not say to carry on
    ("keep going, don't stop") nor ask whether it could ("would you be able to stop dead, if I
    shouted?": text test v32): then its stop or cancel runs even where nothing reads as a request."""
    return intent is not None and not intent.carries_on and intent.refusal is not ClauseKind.ABILITY and any(
        _HALTING.search(c.text) for c in staying(intent).clauses)
