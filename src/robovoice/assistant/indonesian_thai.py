"""Indonesian, Malay and Thai said inside English, as grandparents, helpers and grandchildren in
those homes say it: please, thank you, don't, later, now, the polite particles and the kin titles
before a name put in English, for the reading only (text test v113: "Front door, please krub" was
talk, "Tolong call Anna" no request, "switch the projector on ya" a switch for "you").

Nothing is rewritten unless a word only these languages have was said (`_MARKER`). A particle is
dropped only where it ends a clause ("…, ya", "…, krub"); a title ("Tante Anna", "Om Ben", "Khun
Clara") is dropped only before a capitalised name, so the robot's contacts read the name.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_MARKER = re.compile(r"\b(?:tolong|krub|khrap|khrup|krap|kha|dong|sih|nanti|nggak|ngga|gak|enggak|jangan|sekarang"
                     r"|cepat|cepetan|terima kasih|makasih|khob ?khun|kop ?khun|mai pen rai|sekejap|kejap|nenek"
                     r"|atok|tante|cucu|ayo|yuk|tak nak|tak payah|na ka|nakha|nid nueng|reo reo|rew rew)\b",
                     re.IGNORECASE)

_END = r"(?=\s*(?:[,.!?;\u2026]|$))"  # where a clause ends

_RULES = rules((
    (r"\b(?:terima kasih|makasih|khob ?khun|kop ?khun)(?: (?:ya|krub|khrap|kha|ka|na))?\b", "thank you"),
    (r"\btolong\b", "please"), (r"\b(?:jangan|tak nak|tak payah)\b", "don't"), (r"\bmai pen rai\b", "never mind"),
    (r"\bnanti(?: (?:saja|aja|ya))?\b", "later"), (r"\bsekarang\b", "now"), (r"\b(?:sekejap|kejap)\b", "wait a moment"),
    (r"\b(?:cepat|cepetan|reo reo|rew rew)\b", "quickly"), (r"\b(?:nggak|ngga|gak|enggak)\b", "no"),
    (r"^(?:(?:ayo|yuk)\b[\s,!.\u2026]*)+", ""),
    # the polite particles and a "ya" said as a tag, where they end a clause
    (r"[\s,]*\b(?:krub|khrap|khrup|krap|kha|ka|na ka|nakha|na|ja|dong|sih|deh|ya|yah|lah|nid nueng)\b" + _END, ""),
    # a kin title before a name: the name the robot's contacts have
    (r"\b(?:tante|om|oma|opa|nenek|atok|pak|bu|ibu|mbak|mas|kak|khun|pi|nong|yai|ta)\s+(?=(?-i:[A-Z])[a-z])", ""),
))


def from_indonesian_thai(text: str) -> str:
    """`text` with its Indonesian, Malay and Thai put in English; unchanged where no word only they have was said."""
    return rewrite_where(_MARKER, text, _RULES)
