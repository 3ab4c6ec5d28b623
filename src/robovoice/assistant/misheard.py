"""Words speech-to-text writes for others, put back where only one reading makes sense, for the
reading only (the model reads the transcript as it came).

- "the project or" for "the projector" (audio test v104: "Switch off the project or go to the
  bathroom, then call Anna" was read as one thing or the other, and the drive never made);
- "a bag" for Nigerian "abeg" (please) (audio test v105: "a bag go to the kitchen." was talk);
- "coil" for "call" after the words that end one (audio tests v102, v103: "Finish the coil now");
- "the dock top" for "the doctor" after "call" (audio test v108);
- "end" for "and" or "then" before a room (audio test v112: "go to the hallway, end the front door,
  and call Anna" ended no call and never went to the front door): nothing ends a room;
- "end for the hallway" for "head for the hallway" (audio test v121: the drive was never made);
- no comma after a "no" between two rooms (audio test v113: "bathroom, no hallway, hallway, go
  there" took the hallway back and drove to the bathroom).
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import ROOM

_ABEG_HEARD = re.compile(r"^(?:a bag|a beg|uh beg),?\s+(?=(?:go|come|call|ring|switch|turn|put|take|bring)\b)",
                         re.IGNORECASE)
_COIL = re.compile(r"\b(hang up|finish|end|stop|close|cut)\s+(?:the |this |that )?coil\b", re.IGNORECASE)
_DOCK_TOP = re.compile(r"(?<=\bcall )the (?:dock top|dock tor|doc top|dog tor)\b", re.IGNORECASE)
_PROJECT_OR = re.compile(r"\b(the|that|your|my|this) project or\b(?=\s+(\w+)|)", re.IGNORECASE)
_NO_ROOM = re.compile(r"\b(" + ROOM + r"),?\s+no\s+(?=(?:the |your |my )?" + ROOM + r"\b)", re.IGNORECASE)
_END_ROOM = re.compile(r"(?<=, )end (?=(?:the |your |my )?" + ROOM + r"\b)", re.IGNORECASE)
_END_FOR = re.compile(r"\bend (?=(?:for|towards?) (?:the |your |my )?" + ROOM + r"\b)", re.IGNORECASE)


def heard_right(text: str, imperatives: frozenset[str]) -> str:
    """`text` with each word speech-to-text misheard put back; `imperatives`: the verbs a command
    run on after a misheard "projector" starts with (a clause of its own)."""
    text = _PROJECT_OR.sub(lambda m: f"{m.group(1)} projector" + ("," if m.group(2) in imperatives else ""), text)
    text = _ABEG_HEARD.sub("please ", text)
    text = _COIL.sub(r"\1 the call", text)
    text = _DOCK_TOP.sub("the doctor", text)
    text = _END_FOR.sub("head ", text)
    return _NO_ROOM.sub(r"\1, no, ", _END_ROOM.sub("then ", text))
