"""French said inside English, as in Montreal and the rest of Quebec: the requests, negations,
order words and rooms put in English, for the reading only (text test v95: "Allume le
projecteur, turn it on please", "Appelle ma fille, Anna", "hang up with Anna, pis appelle le
docteur Weber" were refused or half done).

A Québécois speaker drops the "ne" of a negation ("appelle-la pas": don't call her), says "pis"
for then and "la porte d'en avant" for the front door. Nothing is rewritten unless a word only
French has was said (`_MARKER`); "ferme", "salon" and "base" alone are English too.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_VERB = r"(?:allume|éteins|eteins|ferme|appelle|téléphone|va|viens|raccroche|arrête|arrete|retourne|reviens)"
_MARKER = re.compile(r"\b(?:allume|éteins|eteins|appelle|raccroche|arrête|s'il (?:te|vous) pla[iî]t|merci|pis"
                     r"|après ça|d'abord|ensuite|première chose|premièrement|pas maintenant|plus tard|demain"
                     r"|tantôt|la cuisine|le salon|la chambre|la salle de bains?|la porte d'en avant|porte d'entrée"
                     r"|le projecteur|projecteur|ma fille|mon fils|le docteur|la voisine|va (?:à|au|dans|voir)"
                     r"|viens (?:ici|icitte|à|au|dans)|retourne|reviens|icitte)\b", re.IGNORECASE)

_RULES = rules((
    (r"\bs'il (?:te|vous) pla[iî]t\b", "please"), (r"\bmerci(?: beaucoup)?\b", "thank you"),
    (r"^(?:(?:bon|voyons|coudonc|tsé|ok là|allô)\b[\s,!.]*)+", ""),  # openers ("ben" is Ben too: kept)
    # not now, later; "appelle-la pas" / "n'appelle pas": don't call (the "ne" often unsaid)
    (r"\bpas (?:tout de suite|maintenant|là)\b", "not now"), (r"\bplus tard\b|\btantôt\b", "later"),
    (r"\bdemain\b", "tomorrow"), (r"\b(?:à soir|ce soir)\b", "tonight"), (r"\bavant ça\b", "before that"),
    (r"\b(?:ne |n')?(" + _VERB + r")(?:-(?:le|la|les|moi|lui))? pas\b", r"don't \1"),
    # order words
    (r"\bet (?:après|ensuite|pis|puis)\b", "and then"), (r"\b(?:pis|puis|ensuite|après ça)\b", "then"),
    (r"\b(?:première chose|premièrement|d'abord)\b", "first"), (r"\bet\b", "and"),
    # rooms, people and the projector ("le docteur Weber": Doctor Weber)
    (r"\b(?:the |la |le |l')?cuisine\b", "the kitchen"), (r"\b(?:the |le )?salon\b", "the living room"),
    (r"\b(?:the |la )?chambre(?: à coucher)?\b", "the bedroom"),
    (r"\b(?:the |la )?(?:salle de bains?|toilette)\b", "the bathroom"),
    (r"\b(?:the |le )?(?:couloir|corridor)\b", "the hallway"),
    (r"\b(?:the |la )?porte (?:d'en avant|d'entrée|avant)\b", "the front door"),
    (r"\b(?:the |le )?chargeur\b", "the charger"),
    (r"\b(?:the |le |ce |mon )?projecteur\b", "the projector"), (r"\bma fille\b", "my daughter"),
    (r"\bmon fils\b", "my son"), (r"\b(?:le )?(?:docteur|médecin)\b", "Doctor"),
    (r"\bla voisine\b", "the neighbour"),
    # verbs: "va à la cuisine" is "go to the kitchen" (the room is in English above)
    (r"\ballume(?:-(?:le|la|moi))?\b", "turn on"),
    (r"\b(?:éteins|eteins|ferme)(?:-(?:le|la|moi))?(?: ça)?\b", "turn off"),
    (r"\b(?:appelle|téléphone)(?:-(?:la|le|les|moi))?\b", "call"), (r"\braccroche\b", "hang up"),
    (r"\b(?:arrête|arrete)\b", "stop"),
    (r"\b(?:va|viens|retourne|reviens)(?: voir)? (?:à |au |aux |dans |en )?(?=the )", "go to "),
    (r"\bviens (?:ici|icitte)\b", "come here"), (r"\b(?:retourne|reviens)\b", "come back"),
    (r"\b(turn (?:on|off)),\s+(?=the projector\b)", r"\1 "),  # "ferme-moi ça, le projecteur"
))


def from_french(text: str) -> str:
    """`text` with its French put in English; unchanged where no French word was said."""
    return rewrite_where(_MARKER, text, _RULES)
