"""Persian (Farsi) and Dari said inside English, as Iranian and Afghan grandparents, their children
and carers say it: please, thank you, no, openers, calls, order and time words put in English, for
the reading only (text test v108: "Now hallway, lutfan" and "You call him for me, lotfan?" were
talk, "Agha! Bedroom. Baleh?" a question).

Nothing is rewritten unless a word only these languages have was said (`_MARKER`): "merci" is
French too, "baba" a child's word, "Jan", "Alan" and "Aga" names or a cooker, so none marks
Persian. "Baleh" (yes) after a request is a tag asking "all right?", not an answer.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_MARKER = re.compile(r"\b(?:lotfan|lutfan|lotfen|tashakor|tashakkor|mamnoon|mamnun|mersi|mehrbani|meherbani|baleh"
                     r"|joon|jaan|khanum|khanom|agha|farda|baadan|ba'?dan|aval|avval|hala|zood|zud"
                     r"|bebakhshid|befarmayid|befarma|khahesh mikonam|khoda hafez|nakon|nakonid|boro|biya)\b",
                     re.IGNORECASE)

_RULES = rules((
    (r"\b(?:lotfan|lutfan|lotfen|khahesh mikonam|befarma(?:yid)?)\b", "please"),
    (r"\b(?:tashakk?or|mamnoon|mamnun|mersi|merci|mehrbani|meherbani)(?: (?:mikonam|az shoma))?\b", "thank you"),
    (r"\bbebakhshid\b", "excuse me"), (r"\b(?:nakon|nakonid)\b", "don't"),
    # openers, calls and a yes said as a tag: "Agha! Bedroom. Baleh?", "Maman joon, …"
    (r"^(?:(?:agha|khanum|khanom|ey|ay|vay|bah)\b[\s,!.\u2026]*)+", ""),
    (r"(?<=\w)[\s,.!]*\bbaleh\s*\?", ", please?"), (r"\bbaleh\b", "yes"), (r"\b(?:joon|jaan)\b", "dear"),
    # order and time words: "aval the kitchen", "baadan call Ben", "farda"
    (r"\b(?:aval|avval)\b", "first"), (r"\b(?:baadan|ba'?dan)\b", "then"), (r"\bhala\b", "now"),
    (r"\bfarda\b", "tomorrow"), (r"\b(?:zood|zud)(?: bash)?\b", "quickly"),
    (r"\bboro\b", "go"), (r"\bbiya\b", "come"),
))


def from_persian(text: str) -> str:
    """`text` with its Persian and Dari put in English; unchanged where no word only they have was said."""
    return rewrite_where(_MARKER, text, _RULES)
