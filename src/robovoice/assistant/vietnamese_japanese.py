"""Vietnamese and Japanese said inside English, as grandparents from Vietnam and Japan and their
families say it: no, not yet, please, thank you, time words, particles and openers put in English,
for the reading only (text test v107: "Turn off projector... ơ, không, leave it on" switched it
off: the Vietnamese "no" took nothing back).

Nothing is rewritten unless a word only these languages have was said (`_MARKER`): "dame", "oi",
"ano" and "ba" are English or Spanish words too. "Vâng", "dạ" and "hai" (yes) are left as said: a
yes asks nothing here, and "hai" is also Hindi.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_MARKER = re.compile(r"\b(?:không|khong|chưa|nhé|nhe|nha|vâng|dạ|cảm ơn|cam on|làm ơn|lam on|bây giờ|bay gio|đừng"
                     r"|ơi|bà|ông|con ơi|onegai(?: shimasu)?|arigat[oō]u?(?: gozaimasu)?|chotto|sumimasen|hayaku"
                     r"|mada|ato de|ojii ?chan|obaa ?chan|okaa ?san|otou ?san|jiichan|baachan)\b"
                     r"|(?<!\w)(?:ạ|ơ)(?!\w)", re.IGNORECASE)

_RULES = rules((
    (r"\b(?:chưa|chua|mada)\b", "not yet"), (r"\b(?:không|khong)\b", "no"), (r"\bđừng\b", "don't"),
    (r"\b(?:làm ơn|lam on|onegai(?: shimasu)?)\b", "please"),
    (r"\b(?:cảm ơn|cam on|arigat[oō]u?(?: gozaimasu)?)\b", "thank you"), (r"\bsumimasen\b", "excuse me"),
    (r"\b(?:bây giờ|bay gio)\b", "now"), (r"\bato de\b", "later"), (r"\bhayaku\b", "quickly"),
    (r"\bchotto matte\b", "wait"),
    # particles, openers and calls, which ask nothing: "ơ, …", "ano…", "…, nhé", "bà ơi"
    (r"(?<!\w)(?:ơ|ạ)(?!\w)|\bơi\b|\b(?:chotto|anou?|ano ne|eto|etto)\b", ""),
    (r"\s*,?\s*\b(?:nhé|nhe|nha|ne|yo)\b(?=\s*(?:[,.!?\u2026]|$))", ""),
    (r"^[\s,.\u2026]+|(?<=[,.])\s*[,.\u2026]+", ""),
))


def from_vietnamese_japanese(text: str) -> str:
    """`text` with its Vietnamese and Japanese put in English; unchanged where no word only they have was said."""
    return rewrite_where(_MARKER, text, _RULES)
