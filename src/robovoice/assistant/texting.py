"""A message typed the way a young carer texts: no full stops, "lol" where a sentence ends, "+"
for "and", the "I" left off "need you …". Said with its sentences and subject back, for the reading
only (text test v118: "ok im done talking to anna u can hang up now ty" and "need u in the bathroom
asap …" were talk, "switch off the projector + call dr weber" one request).

Runs after the texting shorthand is spelled out (`lexicon.plain`: "u" is "you" here).
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite, rules

# a clause that asks, run on after one that tells: a sentence of its own ("…to anna you can hang up now")
_ASKED_AFTER_RE = re.compile(
    r"(?<=\w)(?<!\bso)(?<!\bif)(?<!\bwhen)(?<!\bthat)(?<!\bas)(?<!\bbecause)(?<!\bcause)(?<!\bcuz)"
    r"(?<!\buntil)(?<!\btill)(?<!\band)(?<!\bbut)(?<!\bthen)(?<!\bor)(?<!\bonce)(?<!\bwhere)"
    r" (?=you can (?:now )?(?:hang up|end|stop|go|come|call|ring|switch|turn|put|head|charge)\b)", re.IGNORECASE)

_RULES = rules((
    (r"\s+\+\s+", " and "),  # "switch off the projector + call dr weber"
    # "lol", "lmao", "haha": where a sentence ends (and nothing, said last)
    (r"\s+\b(?:lol|lmao|lmfao|haha+|hehe+|xd)\b[\s.!]*(?=\w)", ". "), (r"\s+\b(?:lol|lmao|lmfao|haha+|xd)\b\W*$", ""),
    # "grandads bedroom please he wants you": a courtesy, then a sentence of its own
    (r"\b(please|thank you|thanks|asap|right now)\s+(?=(?:he|she|they|i|we|it|my|mum|dad|nan|gran|grandma|grandad)\b)",
     r"\1. "),
    (r"\b(asap|right now)\s+(?=the\b)", r"\1. "),  # "… right now the pot is boiling over"
    # "need you in the bathroom", "lowkey need you to call ben": the "I" left off (a request, as with it)
    (r"(^|[.!?]\s+)((?:(?:ok|okay|so|please)\s+)*)((?:(?:highkey|honestly|really)\s+)?)need you\b",
     r"\1\2I \3need you"),
))


def from_texting(text: str) -> str:
    """`text` with a texted message's sentences and left-off "I" put back (unchanged without them).
    A request run on after a statement is split off only in a message with no stop, comma or
    question mark at all ("Not now, but after the dinner you can put the projector on" is one)."""
    unstopped = not re.search(r"[.,!?;:]", text)
    text = rewrite(text, _RULES)
    return _ASKED_AFTER_RE.sub(". ", text) if unstopped else text
