"""Speech that searches for its words, as after a stroke (aphasia) or in a hurry, said as it
would be written once the word is found: a word said again after a pause ("Go... go plug in",
"Then... then call Ben"), a part-word then the word ("pro... projector"), a thing then its state
after a pause ("the projector... on"). For the reading only; the model reads the person's words.

Text test v122 (stroke survivors): "Then... then call Ben" left "Kitchen." before it as talk,
"pro... projector. On." was three steps, and "Go... go plug in" a drive to "you". A call said as
"the talking" or "the chat" ("Stop the... the talking. Hang up.") stopped the robot's motion:
it is the call's end.
"""

from __future__ import annotations

import re

_PAUSE = r"\s*(?:\.{2,}|\u2026|\s-\s|\s\u2014\s)\s*"
# a word or a few, a pause, the same words again: said once ("the... the" is `lexicon._HESITATION`'s;
# "I'd like to... I'd like to see Clara's face", text test v127)
_WORDS = r"\w+(?:['\u2019]\w+)?"
_SAID_AGAIN = re.compile(rf"\b({_WORDS}(?:\s+{_WORDS}){{0,3}})" + _PAUSE + r"(\1)\b", re.IGNORECASE)
# a verb said again after a comma: "Go, go to the bathroom" (text test v127) is one "go"
_VERB_AGAIN = re.compile(r"\b(go|come|call|ring|switch|turn|put|get|take|hang|end)\s*,\s*(\1)\b", re.IGNORECASE)
# a part of a word, a pause, the word it starts: "pro... projector", "ki... kitchen"
_PART_WORD = re.compile(r"\b(\w{2,})(?:\.{2,}|\u2026|-)\s*(?=(\w+))", re.IGNORECASE)
# a thing named, a pause, its state ending the clause: "the projector... on", "Projector. On."
_THING_THEN_STATE = re.compile(r"\b(projector|telly|tv|screen)(?:\s*(?:\.{2,}|\u2026|[.,])\s*)(on|off)"
                               r"(?=\s*[.,!?]|\s*$)", re.IGNORECASE)
# the call, called by what happens in it
_STOP_TALKING = re.compile(r"\b(?:stop|end|finish) the (?:talking|chat|chatting|conversation|natter)\b"
                           r"|\bstop the (?:video )?call\b", re.IGNORECASE)  # "Stop the call with Anna" (v124)


def _part_word(match: re.Match[str]) -> str:
    part, word = match.group(1), match.group(2)
    starts = len(part) < len(word) and word.lower().startswith(part.lower())
    return "" if starts else match.group(0)


def words_found(text: str) -> str:
    """`text` with each word searched for said once, as found."""
    text = _VERB_AGAIN.sub(r"\1", _SAID_AGAIN.sub(r"\2", text))
    text = _PART_WORD.sub(_part_word, text)
    text = _THING_THEN_STATE.sub(lambda m: f"{m.group(1)} {m.group(2).lower()}", text)
    return _STOP_TALKING.sub("end the call", text)
