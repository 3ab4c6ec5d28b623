"""The local "stop" keyword: recognised from a transcript without any LLM (DESIGN.md §8).

A transcript is a stop command when, after removing punctuation, the wake phrase and a few
fillers ("please", "now", "robot", "okay", ...), nothing is left but a stop phrase ("stop",
"stop the robot", "halt", "stop moving", "freeze", repeated or not). Anything more ("stop
the call", "don't stop", "stop at the kitchen") is not: that is for the model.
"""

from __future__ import annotations

import re
from typing import Final

STOP_PHRASES: Final = frozenset({
    "stop", "halt", "freeze", "stop the robot", "stop robot", "stop moving", "stop driving", "stop it",
    "stop right there", "stop there", "stop now", "stop right now", "emergency stop", "stop stop",
})  # fmt: skip
_FILLERS: Final = ("please", "right now", "now", "immediately", "okay", "ok", "hey", "jarvis", "robot",
                   "oh", "hey robot", "you")  # fmt: skip
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
    # strip fillers from both ends ("hey jarvis stop please", "okay robot halt now")
    changed = True
    while changed and tokens:
        changed = False
        for filler in sorted(_FILLERS, key=len, reverse=True):
            f = filler.split()
            if tokens[: len(f)] == f and len(tokens) > len(f):
                tokens = tokens[len(f) :]
                changed = True
            if tokens[-len(f) :] == f and len(tokens) > len(f):
                tokens = tokens[: -len(f)]
                changed = True
    phrase = " ".join(tokens)
    if phrase in STOP_PHRASES:
        return True
    return bool(tokens) and all(t in ("stop", "halt") for t in tokens)
