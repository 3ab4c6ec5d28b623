"""Afrikaans and isiZulu said inside South African English: the requests, negations and
courtesy put in English, for the reading only (text test v94: "Ry gou na die kitchen and
phone my daughter Anna when you get there" read as talk, and the call was lost).

South Africans at home switch into Afrikaans for the verb and the little words ("ry/gaan na
die …": drive/go to the …, "bel": ring, "skakel … aan/af": switch on/off, "moenie … nie":
don't, "nie nou nie": not now, "asseblief": please) and into isiZulu for courtesy ("ngiyacela":
please, "hamba": go). Nothing is rewritten unless a word only these languages have was said
(`_MARKER`): "die", "loop", "gang" and "more" are English too.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_BEL = r"(?-i:[Bb]el)(?= (?-i:[A-Z])| my\b)"  # "bel Anna": ring her (not Bel, a name, alone)
_MARKER = re.compile(r"\b(?:na die|asseblief|asb|dankie|moenie|nie|nog nie|netnou|gou|kombuis|badkamer|slaapkamer"
                     r"|sitkamer|voordeur|laaier|skakel|aanskakel|afskakel|aan|af|sit die|maak die|kom hier|vir my"
                     r"|ngiyacela|ngicela|ngiyabonga|hamba|yebo|haibo|" + _BEL + r")\b", re.IGNORECASE)

_RULES = rules((
    # courtesy and openers: "asseblief" and "ngiyacela" are please; "ag", "eish", "haibo" open a request
    (r"\b(?:asseblief(?: tog)?|asb|ngiyacela|ngicela)\b", "please"),
    (r"\b(?:baie )?dankie\b|\bngiyabonga\b", "thank you"), (r"\bvir my\b", "for me"),
    (r"\bvir (?=(?-i:[A-Z]))", ""),  # "bel vir Anna": "vir" marks who is rung
    (r"^(?:(?:ag|eish|haibo|yoh|yebo|ja|toe)\b[\s,!.]*)+", ""),
    # negations first: "moenie … nie" is one "don't" (the "nie" closes it); "nie nou nie": not now
    (r"\bnie nou nie\b", "not now"), (r"\bnog nie\b", "not yet"), (r"\bnetnou\b", "later"),
    (r"\bmoenie\b", "don't"), (r"\s*\bnie\b(?=\s*(?:[,.!?]|$))", ""),
    # places, and the ways to them: "ry/gaan/loop/kom (gou) na die X": drive/go/come (quickly) to the X
    (r"\bkombuis\b", "kitchen"), (r"\bbadkamer\b", "bathroom"), (r"\bslaapkamer\b", "bedroom"),
    (r"\bsitkamer\b", "living room"), (r"\bvoordeur\b", "front door"), (r"\blaaier\b", "charger"),
    (r"\b(?:ry|gaan|loop|hardloop|hamba)(?:\s+gou)?\s+na\s+die\b", "go to the"),
    (r"\bkom(?:\s+gou)?\s+na\s+die\b", "come to the"), (r"\bkom hier(?:heen)?\b", "come here"),
    (r"\bna die\b", "to the"), (r"\bhamba\b", "go"), (r"\bgou\b", "quickly"),
    # switching: "skakel/sit die projector aan" (on), "… af" (off); "bel/skakel Anna": call
    (r"\b(?:skakel|sit|maak)\s+die\s+(\w+)\s+aan\b", r"switch the \1 on"),
    (r"\b(?:skakel|sit|maak)\s+die\s+(\w+)\s+af\b", r"switch the \1 off"),
    (r"\baanskakel\b", "switch on"), (r"\bafskakel\b", "switch off"),
    (r"\b(?:" + _BEL + r"|skakel)\b", "call"),
    # the little words between: "en dan" (and then), "my seun/dogter" (son, daughter), "die" (the)
    (r"\ben dan\b", "and then"), (r"\bdan\b", "then"), (r"\bseun\b", "son"), (r"\bdogter\b", "daughter"),
    (r"\bdie\b", "the"),
))


def from_afrikaans(text: str) -> str:
    """`text` with its Afrikaans and isiZulu put in English; unchanged where none was said."""
    return rewrite_where(_MARKER, text, _RULES)
