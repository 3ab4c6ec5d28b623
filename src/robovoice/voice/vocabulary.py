"""Speech-to-text hints: the words this robot's users are likely to say.

A small speech model mishears rare words ("end the call" as "and Macau", "Anna" as
"Atlanta") far less when it is told what to expect. Whisper takes such a hint as its
``initial_prompt`` (text it treats as what was said just before). The hint is built from
what the robot already declares, so nothing is written twice:

- the wake phrase;
- each tool's name as words ("start_video_call" -> "start video call");
- the values listed in the tools' parameter schemas: ``enum`` and ``examples`` (JSON
  Schema keywords; a manifest lists its place names, contacts, ... there);
- extra words from the configuration (``[voice] vocabulary``);
- the stop words.

A short utterance heard while the robot moves (no wake word) is only checked for a stop,
so it gets a hint of stop words alone (`STOP_HINT`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import Any

from robovoice.llm.base import ToolSpec

STOP_HINT = "Stop! Halt! Stop the robot! Stop, stop!"
# Whisper keeps at most 223 prompt tokens (the last ones); about 3 characters per token
# leaves room and keeps the hint's decoding cost small.
MAX_HINT_CHARS = 600


def _schema_values(schema: Mapping[str, Any]) -> Iterator[str]:
    """String values of ``enum``/``examples``/``const`` anywhere in a JSON Schema."""
    for key in ("enum", "examples"):
        values = schema.get(key)
        if isinstance(values, list):
            yield from (v for v in values if isinstance(v, str))
    if isinstance(schema.get("const"), str):
        yield schema["const"]
    for key in ("properties", "$defs", "definitions"):
        children = schema.get(key)
        if isinstance(children, Mapping):
            for child in children.values():
                if isinstance(child, Mapping):
                    yield from _schema_values(child)
    for key in ("items", "anyOf", "oneOf", "allOf"):
        children = schema.get(key)
        for child in children if isinstance(children, list) else [children]:
            if isinstance(child, Mapping):
                yield from _schema_values(child)


def _unique(words: Iterable[str]) -> list[str]:
    seen: set[str] = set()
    out: list[str] = []
    for word in words:
        word = " ".join(word.split())
        if word and word.lower() not in seen:
            seen.add(word.lower())
            out.append(word)
    return out


def command_hint(wake_phrase: str, tools: Sequence[ToolSpec], extra: Sequence[str] = ()) -> str:
    """The hint for an addressed command (see the module docstring), at most
    `MAX_HINT_CHARS` long: the wake phrase and stop words always fit; tool words and
    vocabulary are cut from the end when there are too many."""
    wake = wake_phrase.strip().title()
    head = f"{wake}." if wake else ""
    actions = _unique(tool.name.replace("_", " ") for tool in tools)
    names = _unique([*extra, *(value for tool in tools for value in _schema_values(tool.parameters))])
    parts = [", ".join(actions) + "." if actions else "", ", ".join(names) + "." if names else ""]
    body = " ".join(p for p in parts if p)
    room = MAX_HINT_CHARS - len(head) - len(STOP_HINT) - 2
    if len(body) > room:
        body = body[: max(0, room)].rsplit(",", 1)[0] + "."
    return " ".join(p for p in (head, body, STOP_HINT) if p)


# Whisper hears a quickly said "Doctor" before a surname as "dock to" ("Please call, dock to
# Weber."; audio tests v4 and v6; "dock for Weber", "dock or Weber" on dev clips of
# audio-dev-ring), and "dock" then reads as a request to drive to the dock.
_DOCTOR_HEARD_AS = r"\b(?:dock|doc|dog|duck)[,.]?\s+(?:to|too|two|ter|tor|for|four|or)\s+"
_TITLED = re.compile(r"\bDr\.?\s+([A-Z][\w'-]+)")


def restore_titles(text: str, hint: str) -> str:
    """`text` with "dock to Weber" written "Dr. Weber" for each "Dr. <name>" in the hint (the
    names the robot knows): the title, not a place."""
    for surname in set(_TITLED.findall(hint)):
        text = re.sub(_DOCTOR_HEARD_AS + re.escape(surname) + r"\b", f"Dr. {surname}", text, flags=re.IGNORECASE)
    return text


# Speech-to-text hears a short "end the call" as "and the call", above all over a remote voice
# (CI, 27 Nov 2026), and the words then read as talk. Only a whole utterance of "and" plus an
# end_* tool's subject words is restored: "and the call, was it long?" stays as heard.
_END_ACTION = re.compile(r"\bend((?: [a-z]+)+)(?=[,.])")
# … or one followed by the next step asked ("and the call and then head back to your dock", audio
# test v53): a verb of the robot's after "then"; "and the call and then he rang off" stays as heard
_NEXT_STEP = (r",?\s+(?:and\s+)?then\s+(?=(?:head|go|come|drive|move|get|take|turn|switch|put|pop|nip|call|ring|"
              r"phone|return|back)\b)")


def restore_end(text: str, hint: str) -> str:
    """`text` "And the call." written "End the call." when the hint names an end_* action
    ("end video call") whose subject words are all the rest of `text`."""
    for subject in _END_ACTION.findall(hint):
        words = subject.split()
        tail = r"(?:the\s+)?" + "".join(rf"(?:{re.escape(w)}\s+)?" for w in words[:-1]) + re.escape(words[-1])
        restored = re.sub(rf"^\s*and\s+({tail})(\s*(?:,?\s*please)?[.!]*\s*$|{_NEXT_STEP})", r"End \1\2", text,
                          flags=re.IGNORECASE)
        if restored != text:
            return restored
    return text


# Whisper tiny.en hears "ring" before a name as "bring" ("Hey Jarvis, bring Clara."): 12 of the
# 32 dev clips of audio-dev-ring (3 more before "dock to/for/or Weber"), and once in each of
# audio tests v20, v21 and v22; "bring Anna" then reads as a drive to "Anna". A robot that can
# call but not carry has no other use for "bring" plus a name it can call and nothing after it
# ("bring Ben his tea" stays as heard).
_CALL_ACTION = re.compile(r"\b(?:start|make|place)(?: video| voice| phone)? call\b")
_NAME_ITEM = re.compile(r"(?<=[,.] )((?:Dr\. )?[A-Z][\w'-]+(?: [A-Z][\w'-]+)*)(?=[,.])")
_BEFORE_BRING = r"(^|[,.;!?]\s*|\b(?i:and|then|please|you|just|now|so|also|first)\s+)"
_AFTER_NAME = r"(?=\s*(?:[,.;!?]|$|(?i:for me|please|now|and|then|up|on video|straight away|right away)\b))"


def _callable(hint: str) -> str | None:
    """A pattern for a name the hint's call action can call ("Dr. Weber", "Ben"), or None when
    the hint names no call action or no name."""
    if not _CALL_ACTION.search(hint):
        return None
    names = {re.sub(r"^Dr\. ", "", name) for name in _NAME_ITEM.findall(hint)}
    if not names:
        return None
    listed = "|".join(re.escape(n) for n in sorted(names, key=len, reverse=True))
    return r"(?:(?i:dr|doctor|doc)\.?\s+)?(?:" + listed + r")\b"


def restore_ring(text: str, hint: str) -> str:
    """`text` with "bring <name>" written "ring <name>" when the hint names a call action and
    <name> is one of the names it lists, at the start of a clause and at the end of one."""
    if (who := _callable(hint)) is None:
        return text
    pattern = _BEFORE_BRING + r"([Bb])ring(\s+(?:(?i:our|my)\s+)?" + who + ")" + _AFTER_NAME  # "bring our Anna"
    return re.sub(pattern, lambda m: m[1] + ("R" if m[2] == "B" else "r") + "ing" + m[3], text)


# … and hears "…, then call Ben" as "…, end call, Ben" (audio tests v34 and v37: the call never
# made, the end of a call that was not running failed). Ending a call says no name that way;
# after another request and before a name the robot can call, it is the call.
def restore_then_call(text: str, hint: str) -> str:
    """`text` with ", (and) end call, <name>" or " and end call <name>" written "… then call <name>"."""
    if (who := _callable(hint)) is None:
        return text
    # (or after a bare "and": "go to the living room and end call Anna", audio test v118)
    pattern = r"([,;]\s*(?:(?i:and)\s+)?|\s(?i:and)\s+)(?i:end) call,?\s+(" + who + ")" + _AFTER_NAME
    return re.sub(pattern, lambda m: m[1] + "then call " + m[2], text)


# … and "then" as "Ben": after a call to another ("call Anna, then head to the hallway" heard as
# "call Anna, Ben, head to the hallway", audio test v39: the call to Anna read as corrected to
# Ben, and the drive never made), right before a verb of motion or switching, and after "and"
# right before a call to another ("…, and then ring Doctor Weber" heard as "…, and Ben Ring, Dr.
# Weber", audio test v40). Said after a comma or an "and", not after a full stop: an aside to a
# Ben in the room ("Call Anna. Ben, head to the hallway.") stays as said.
_NEXT_VERB = r"(?=(?i:go|head|drive|come|switch|turn|put|pop|nip|take|get|move|return)\b)"


def restore_then_after_call(text: str, hint: str) -> str:
    """`text` with "call <name>, Ben, <verb>" written "call <name>, then <verb>", and ", and Ben
    ring, <name>" written ", and then ring <name>" (Ben: a name the hint's call action lists,
    said as "then")."""
    if (who := _callable(hint)) is None or not re.search(r"\bBen\b", hint):
        return text
    pattern = r"(\b(?i:call|ring|phone|video call)\s+(?!Ben\b)" + who + r"),\s+Ben,?\s+" + _NEXT_VERB
    text = re.sub(pattern, r"\1, then ", text)
    pattern = r"(,\s*(?i:and)\s+)Ben,?\s+((?i:ring|call|phone)),?\s+(?=(?!Ben\b)" + who + ")"
    return re.sub(pattern, lambda m: m[1] + "then " + m[2].lower() + " ", text)


# A hesitation before the command ("er, go to the kitchen, would you") heard as "or go to the kitchen,
# would you?" (audio test v44): an utterance does not open with "or" before a verb; the reading took the
# request for talk. Only at the very start, before one of the request verbs.
_OPENING_OR = re.compile(r"^\s*or\b[\s,]*" + _NEXT_VERB.replace("take|get", "take|get|ring|call|phone|end|stop"),
                         re.IGNORECASE)


def restore_hesitation(text: str) -> str:
    """`text` without an opening "or" right before a verb of the robot's (a heard "er")."""
    return _OPENING_OR.sub("", text)


def restore(text: str, hint: str) -> str:
    """`text` with the mishearings above put right, the title first ("bring dock to Weber" is
    "bring Dr. Weber", then "ring Dr. Weber")."""
    text = restore_then_call(restore_ring(restore_end(restore_titles(restore_hesitation(text), hint), hint), hint),
                             hint)
    return restore_then_after_call(text, hint)
