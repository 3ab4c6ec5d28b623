"""The thing first, then what to do with it, as English shaped by a sign language's grammar puts it
(a Deaf person typing, a terse typist): "projector, turn on please", "Anna call, end", "Charge, you
go?", "After that, you charge go". Said in the order English says them, for the reading only (text
test v112: the projector was never switched on, the call never ended, the charge never asked).

Only these shapes are rewritten; "the projector, is it on?" and "the call ended" are left as said.
"""

from __future__ import annotations

from robovoice.assistant.dialects import ROOM, rewrite, rules

# where a clause starts
_OPENS = r"(^|[.!?,;:\u2026\u2014\u2013-]\s*|\b(?:and|then|but|so|now|first)\s+)"
# the end of a clause, or a courtesy before it
_ENDS = r"(?=\s*(?:[,.!?;:\u2026]|$)|\s+(?:please|now|first|then|quickly)\b)"
_THING = r"(?:the |my |your |that )?(projector|telly|tv|television|screen|lamp|lights?)"

_RULES = rules((
    # "projector, turn on please": the switch said after its thing, with nothing for it to switch after it
    (_OPENS + _THING + r",?\s+(turn|switch|put)\s+(on|off)" + _ENDS, r"\1\3 \4 the \2"),
    # "Projector, off.": one switch, not a thing and then an "off"
    (_OPENS + _THING + r",\s+(on|off)" + _ENDS, r"\1\2 \3"),
    # "Then dock, you go.": the drive, said after its place
    (_OPENS + r"(?:the |your |my )?(" + ROOM + r"|dock|charger|door),\s+(?:you )?go" + _ENDS, r"\1go to the \2"),
    # "Anna call, end", "call, finish now": the end of the call, said after it
    (_OPENS + r"(?:(?:the|this|that|my|(?-i:[A-Z][a-z]+)(?:'s)?) )?(?:video )?call,?\s+"
     r"(?:end|finish|over|done|off|stop)" + _ENDS, r"\1end the call"),
    # "Charge, you go?", "you charge go": the charge asked, its verb said last
    (_OPENS + r"(?:you )?(?:charge|charging|recharge),?\s+(?:you )?go" + _ENDS, r"\1go and charge"),
))


def from_topic_first(text: str) -> str:
    """`text` with a thing said before what to do with it put in English's order (unchanged without)."""
    return rewrite(text, _RULES)
