"""The local "stop" keyword: recognised from a transcript without any LLM (DESIGN.md §8).

A transcript is a stop command when, after removing punctuation, the wake phrase and a few
fillers ("please", "now", "robot", "okay", ...), nothing is left but stop phrases ("stop",
"stop the robot", "halt", "stop moving", "freeze", "hold it right there", "wait, stay where you
are", one or several; "stop my robot" or "stop one of the robot", as Whisper tiny.en hears
"Stop the robot!").
Anything more ("stop the call", "don't stop", "stop at the kitchen") is not: that is for the model.
"""

from __future__ import annotations

import re
from typing import Final

STOP_PHRASES: Final = frozenset({
    "stop", "halt", "freeze", "stop moving", "stop driving", "stop it",
    "stop right there", "stop there", "stop now", "stop right now", "emergency stop", "stop stop", "hold it",
    "hold it right there", "wait", "wait there", "hold on", "stay there", "stay put", "stay where you are",
    "stay right where you are", "stay right there", "don't move", "stop here", "stop right here",
    # idioms people use for the same (text test v25: "Whoa whoa, hold your horses!" during a drive)
    "hold your horses", "hang on", "stand still", "stay still", "stop where you are", "hold still", "keep still",
    "hold up", "quit rolling", "quit moving", "quit driving", "stop rolling",  # Southern US (text test v71)
    "hold",  # said alone ("Hold, hold, …"), and how Whisper tiny.en hears a shouted "Halt!" (audio test v99)
})  # fmt: skip
# With the robot's own voice over it, Whisper tiny.en garbles the little word of "stop the
# robot" ("Stop my robot!", "Stop one robot!", "Stop when robot!", "Stop one of the robot!"):
# "stop", up to three short words, "robot" is a stop ("stop the robot" and "stop robot" too)
_MISHEARD_STOP: Final = re.compile(r"(?:stop|halt)(?: [a-z]{1,4}){0,3} robot"
                                   # and "right" as Whisper hears it: "Stop writing there." (audio test v28)
                                   r"|stop (?:write|writing|rite|wright|riding|ride|righting) there")
_FILLERS: Final = ("please", "right now", "now", "immediately", "okay", "ok", "hey", "jarvis", "robot",
                   "oh", "hey robot", "you", "whoa", "woah", "wow")  # fmt: skip
_FILLER_WORDS: Final = tuple(f.split() for f in _FILLERS)
_WORDS: Final = re.compile(r"[a-z']+")


def normalise(text: str) -> str:
    return " ".join(_WORDS.findall(text.lower().replace("-", " ")))


def is_stop_command(text: str) -> bool:
    """True when `text` (a transcript) is nothing but a stop command."""
    tokens = normalise(text).split()
    # each position reachable from the start by whole fillers and stop phrases, and whether a stop
    # phrase was among them; "robot" is a filler but also part of "stop the robot", so every span
    # is tried ("okay stop the robot right now", "whoa whoa wait stay right where you are")
    reach: dict[int, bool] = {0: False}
    for k in range(len(tokens)):
        if k not in reach:
            continue
        for f in _FILLER_WORDS:
            if tokens[k : k + len(f)] == f:
                reach[k + len(f)] = reach.get(k + len(f), False) or reach[k]
        for j in range(k + 1, len(tokens) + 1):
            span = " ".join(tokens[k:j])
            if span in STOP_PHRASES or _MISHEARD_STOP.fullmatch(span):
                reach[j] = True
    return reach.get(len(tokens), False)


_CLAUSE: Final = re.compile(r"[,.;:!?]+")
_CARRY_ON: Final = re.compile(r"\b(?:don'?t|do not|never|no need to|not) stop\b|\bkeep (?:going|moving|driving)\b"
                              r"|\bcarry on\b", re.IGNORECASE)


def says_stop(text: str) -> bool:
    """For a short utterance without the wake word while the robot moves: a stop command, or a
    transcript with one as a clause of its own and nothing saying to carry on ("Stop, man!" is
    how Whisper hears a quick "Stop there!"; "No, no, stop!"). A needless stop costs less than
    a missed one; with the wake word, `is_stop_command` alone decides (the rest is the model's)."""
    if is_stop_command(text) or _near_stop(text):
        return True
    return not _CARRY_ON.search(text) and any(is_stop_command(part) for part in _CLAUSE.split(text))


# Whisper tiny.en writes a shouted one-word stop as a near miss ("Falt!" for "Halt!", dev audio
# clip nowake-stop-3; "Stob!"): said alone while the robot moves, a word one letter from "stop"
# or "halt" is taken for one ("Salt!" stops it too: a needless stop costs less than a missed
# one). One letter changed, not dropped or added: "What?" and "Top!" are words said alone.
_NEAR: Final = ("stop", "halt")


def _near_stop(text: str) -> bool:
    tokens = [t for t in normalise(text).split() if [t] not in _FILLER_WORDS]
    return len(tokens) == 1 and any(
        len(tokens[0]) == len(word) and sum(a != b for a, b in zip(tokens[0], word, strict=True)) == 1
        for word in _NEAR)
