"""The local "stop" keyword: recognised from a transcript without any LLM (DESIGN.md §8).

A transcript is a stop command when, after removing punctuation, the wake phrase and a few
fillers ("please", "now", "robot", "okay", ...), nothing is left but a stop phrase ("stop",
"stop the robot", "halt", "stop moving", "freeze", "hold it right there", repeated or not;
"stop my robot" or "stop one of the robot", as Whisper tiny.en hears "Stop the robot!").
Anything more ("stop the call", "don't stop", "stop at the kitchen") is not: that is for the model.
"""

from __future__ import annotations

import re
from typing import Final

STOP_PHRASES: Final = frozenset({
    "stop", "halt", "freeze", "stop moving", "stop driving", "stop it",
    "stop right there", "stop there", "stop now", "stop right now", "emergency stop", "stop stop", "hold it",
    "hold it right there",
})  # fmt: skip
# With the robot's own voice over it, Whisper tiny.en garbles the little word of "stop the
# robot" ("Stop my robot!", "Stop one robot!", "Stop when robot!", "Stop one of the robot!"):
# "stop", up to three short words, "robot" is a stop ("stop the robot" and "stop robot" too)
_STOP_THE_ROBOT: Final = re.compile(r"(?:stop|halt)(?: [a-z]{1,4}){0,3} robot")
_FILLERS: Final = ("please", "right now", "now", "immediately", "okay", "ok", "hey", "jarvis", "robot",
                   "oh", "hey robot", "you", "whoa", "woah", "wow")  # fmt: skip
_FILLER_WORDS: Final = tuple(f.split() for f in _FILLERS)
_WORDS: Final = re.compile(r"[a-z']+")


def normalise(text: str) -> str:
    return " ".join(_WORDS.findall(text.lower().replace("-", " ")))


def is_stop_command(text: str) -> bool:
    """True when `text` (a transcript) is nothing but a stop command."""
    words = normalise(text)
    if not words:
        return False
    if words in STOP_PHRASES:
        return True
    tokens = words.split()
    # a stop phrase with nothing but fillers around it ("hey jarvis stop please", "okay stop the
    # robot right now"); "robot" is a filler but also part of "stop the robot", so every span is tried
    for i in range(len(tokens)):
        for j in range(i + 1, len(tokens) + 1):
            span = " ".join(tokens[i:j])
            stop_span = span in STOP_PHRASES or _STOP_THE_ROBOT.fullmatch(span)
            if stop_span and _fillers_only(tokens[:i]) and _fillers_only(tokens[j:]):
                return True
    return all(t in ("stop", "halt") for t in tokens)


def _fillers_only(tokens: list[str]) -> bool:
    """Whether `tokens` is a run of fillers (empty included)."""
    ends = {0}  # positions reachable by whole fillers from the start
    for k in range(len(tokens)):
        if k in ends:
            ends.update(k + len(f) for f in _FILLER_WORDS if tokens[k : k + len(f)] == f)
    return len(tokens) in ends


_CLAUSE: Final = re.compile(r"[,.;:!?]+")
_CARRY_ON: Final = re.compile(r"\b(?:don'?t|do not|never|no need to|not) stop\b|\bkeep (?:going|moving|driving)\b"
                              r"|\bcarry on\b", re.IGNORECASE)


def says_stop(text: str) -> bool:
    """For a short utterance without the wake word while the robot moves: a stop command, or a
    transcript with one as a clause of its own and nothing saying to carry on ("Stop, man!" is
    how Whisper hears a quick "Stop there!"; "No, no, stop!"). A needless stop costs less than
    a missed one; with the wake word, `is_stop_command` alone decides (the rest is the model's)."""
    if is_stop_command(text):
        return True
    return not _CARRY_ON.search(text) and any(is_stop_command(part) for part in _CLAUSE.split(text))

