"""Italian and Greek said inside English, as the grandparents who came to Melbourne, Toronto and
London in the 1960s say it: no, please, thank you, openers, time words and a few requests put in
English, for the reading only (text test v101: "Go to the front door... ochi, wait, hold off"
drove there: the Greek "no" took nothing back).

Nothing is rewritten unless a word only these languages have was said (`_MARKER`); "ne" (Greek
"yes") is left as said: it is too near English's "no" to guess at, and a yes asks nothing here.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_MARKER = re.compile(r"\b(?:[oó]chi|ohi|parakal[oó]|efcharist[oó]|efharist[oó]|[eé]la|siga siga|gr[ií]gora|am[eé]sws"
                     r"|am[eé]sos|[aá]vrio|arg[oó]tera|allora|per favore|per piacere|grazie|subito|piano piano|domani"
                     r"|pi[uù] tardi|aspetta|basta|dai|chiama|spegni|accendi|vai|vieni|andiamo|mamma mia|madonna"
                     r"|po po|opa)\b|(?<!\w)(?:όχι|παρακαλώ|ευχαριστώ)(?!\w)", re.IGNORECASE)

_RULES = rules((
    (r"\b(?:[oó]chi|ohi)\b|(?<!\w)όχι(?!\w)", "no"),  # (before "ela": "ochi, ela" is "no, come on")
    (r"\b(?:parakal[oó]|per favore|per piacere)\b|(?<!\w)παρακαλώ(?!\w)", "please"),
    (r"\b(?:efcharist[oó]|efharist[oó])(?: poli)?\b|\bgrazie(?: mille)?\b|(?<!\w)ευχαριστώ(?!\w)", "thank you"),
    # openers and exclamations, which ask nothing: "Allora... the hallway", "Ela, dai, go to the kitchen"
    (r"^(?:(?:allora|[eé]la|dai|andiamo|mamma mia|madonna(?: mia)?|po po(?: po)?|opa|beh|ecco)\b[\s,!.\u2026]*)+", ""),
    (r"\b(?:subito|am[eé]sws|am[eé]sos)\b", "right now"), (r"\b(?:piano piano|siga siga)\b", "slowly"),
    (r"\bgr[ií]gora\b", "quickly"), (r"\b(?:domani|[aá]vrio)\b", "tomorrow"),
    (r"\b(?:pi[uù] tardi|arg[oó]tera)\b", "later"),
    (r"\baspetta\b", "wait"),
    (r"\bbasta\b(?=\s*(?:[,.!?]|basta\b|$))", "enough"),  # not "basta with the pictures": no end of a call
    (r"\bchiama\b", "call"), (r"\bspegni\b", "turn off"), (r"\baccendi\b", "turn on"),
    (r"\b(?:vai|vieni) (?=(?:to|in|into)\b)", "go "),
))


def from_italian_greek(text: str) -> str:
    """`text` with its Italian and Greek put in English; unchanged where no word only they have was said."""
    return rewrite_where(_MARKER, text, _RULES)
