"""Nepali said inside English, as a Nepali family in Britain or Hong Kong says it, for the
reading only (text test v129: "Off gara", "bathroom tira jaau ta", "Living room ma aaija" and
"…, ani go back to your charging place" were talk).

Nepali puts the verb last ("bathroom tira jaau": towards the bathroom go), makes a verb of an
English word with "gara" (do: "off gara", "Anna lai phone gara": phone to Anna), joins steps
with "ani" (and) and ends a request on a particle ("ta", "na", "hai"). Nothing is rewritten
unless a word only Nepali has was said (`_MARKER`); "ma", "ta", "la" and "ani" alone are
other languages' or English words too.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_DO = r"(?:gara|garnus|garnuhos|gardinus|garideu|gardeu|garnu|gara na|garnus na)"
_GO = r"(?:jaau|jau|janus|jaanus|jaa|jaunus)"
_COME = r"(?:aaija|aija|aaunus|aau|aauna|aaideu)"
_MARKER = re.compile(r"\b(?:" + _DO + "|" + _GO + "|" + _COME + r"|tira|hunchha|huncha|hajur|pachhi|pahila|pahile"
                     r"|chhito|bistarai|ahile|bholi|pardaina|nagara|najau|hoina|dhanyabaa?d|kripaya|hai babu)\b",
                     re.IGNORECASE)
_PLACE = r"((?:the |my |your )?\w+(?: room| door| dock)?)"

_RULES = rules((
    (r"\bdhanyabaa?d\b", "thank you"), (r"\bkripaya\b", "please"),
    # openers and names said to the person: "Hajur, …" (yes, respectfully), "Hunchha, …" (all right)
    (r"(^|[.!?,;\u2026]\s*)(?:hajur|hunchha|huncha)\b[\s,!.]*", r"\1"),
    (r"\s*,?\s*\b(?:hai babu|babu|nani|saab|sahib|hajur)\b(?=\s*(?:[,.!?\u2026]|$))", ""),
    # not now, later, tomorrow, don't
    (r"\bahile (?:hoina|nagara|najau)\b", "not now"), (r"\bahile\b", "now"), (r"\bbholi\b", "tomorrow"),
    (r"\bpardaina\b", "no need"), (r"\bnajau\b", "don't go"), (r"\b(\w+) nagara\b", r"don't \1"),
    # a verb made with "gara": "off gara", "band gara" (shut), "Anna lai phone gara" (phone to Anna)
    (r"\b(?:the )?(projector|screen|tv|telly|light)\s+(on|off)\s+" + _DO + r"\b", r"switch the \1 \2"),
    (r"\b(?:off|band|bandh|banda)\s+" + _DO + r"\b", "switch it off"), (r"\bon\s+" + _DO + r"\b", "switch it on"),
    (r"((?:\b(?:Dr\.?|Doctor) )?\b\w+)\s+lai\s+(?:video\s+)?(?:phone|call|ring)\s+" + _DO + r"\b", r"call \1"),
    (r"\b(?:phone|call|ring)\s+" + _DO + r"\b", "call"),
    # going and coming, the verb last: "bathroom tira jaau", "living room ma aaija"
    (r"\b" + _PLACE + r"\s+(?:tira|ma)\s+" + _GO + r"\b", r"go to \1"),
    (r"\b" + _PLACE + r"\s+(?:tira|ma)\s+" + _COME + r"\b", r"come to \1"),
    (r"\b" + _GO + r"\b", "go"), (r"\b" + _COME + r"\b", "come"),
    # order words, and the particles a request ends on
    # ("pachhi" before what comes next is then, as in Gujarati: "Pehla bedroom, pachhi kitchen", text v132;
    # Gujarati's "pehla" is Nepali's "pahila", first)
    (r"\bani(?: pachhi)?\b", "and then"), (r"\bpachhi\b(?=\s+\w)", "then"), (r"\bpachhi\b", "later"),
    (r"\b(?:pahil[ae]|pehl[ae])\b", "first"),
    (r"\bchhito\b", "quickly"), (r"\bbistarai\b", "slowly"),
    (r"\s+\b(?:ta|na|hai|ni|la)\b(?=\s*(?:[,.!?\u2026]|$))", ""), (r",?\s*\bhoina\s*\?", "?"),  # "…, hoina?": right?
))


def from_nepali(text: str) -> str:
    """`text` with its Nepali requests, order words and particles put in English."""
    return rewrite_where(_MARKER, text, _RULES)
