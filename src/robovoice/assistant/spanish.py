"""Spanish said inside English, as a home-help or a Mexican-American, Colombian or Puerto Rican
family says it: requests, order words, rooms and courtesy put in English, for the reading only
(text test v69: "prende el projector", "ve a la cocina primero"; text test v100: "Ándale, living
room, rápido!" was talk, "la vecina... llámala" was refused, "pero before all that" not heard).

Each word is written so it cannot be an English one: "llama a" (call), not the animal; "ve" not
inside "I've"; "para" (stop, but also "for") not at all. The rooms are put in English only where
a Spanish request or order word was said: "sala" and "puerta" alone are not taken from English.
"Ahorita" is left as said: in Mexico it can mean now or in a while.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite, rules

# Spanish requests, in the familiar and the polite form (text test v69)
_GO = r"(?<!['\u2019])\b(?:ve|vete|vaya|vayas|vayan|váyase|vayase)"
_BACK = r"\b(?:regresa|regrese|vuelve|vuelva)"
_CALL = r"\b(?:llama|llame|llámale|llamale|llámele|llamele)"
_ON = r"\b(?:prende|prenda|enciende|encienda)"
_OFF = r"\b(?:apaga|apague)"
_HANG_UP = r"\b(?:cuelga|cuelgue)"
_ARTICLE = r"(?:\s+(?:el|la|los|las)\b)?"
_COME = r"\b(?:ven|venga)(?= (?:a|al|aquí|aqui|acá|aca)\b)"  # ("venga" alone is Spain's "come on")
_VERB = "|".join((_GO, _BACK, _CALL, _ON, _OFF, _HANG_UP, _COME, r"\b(?:llámala|llamala|llámalo|llamalo)"))
# a request's urging and a speaker's openers, which say no more than "come on" (text test v100)
_URGING = r"(?:ándale|andale|órale|orale|apúrate|apurate|rápido|rapido|híjole|hijole)"

# rooms (and the projector) said in Spanish: an article before them is said in English too
_ROOMS = {"cocina": "kitchen", "baño": "bathroom", "bano": "bathroom", "cuarto": "bedroom",
          "recámara": "bedroom", "recamara": "bedroom", "habitación": "bedroom", "habitacion": "bedroom",
          "dormitorio": "bedroom", "sala": "living room", "pasillo": "hallway",
          "puerta de entrada": "front door", "puerta": "front door", "proyector": "projector"}
_ROOM = re.compile(r"\b(?:(the\s+)|(?:el|la)\s+)?(" + "|".join(sorted(_ROOMS, key=len, reverse=True)) + r")\b",
                   re.IGNORECASE)  # an English "the" before it is kept as said ("al" has made one)
# the rooms are put in English only where a Spanish request or order word was said: "sala" and
# "puerta" alone are not taken from an English sentence
# (a whole word: "very" is not "ve")
_ANY_SPANISH = re.compile("|".join(["(?:" + _VERB + r")\b", r"\b" + _URGING + r"\b",
                                    r"\b(?:después|despues|luego|primero|por favor|pero|gracias)\b"]), re.IGNORECASE)
_YA = re.compile(r"\bya\b", re.IGNORECASE)

_SPANISH = rules((
    # "no la llames": don't call her; "no vayas": don't go (before the verbs below)
    (r"\bno la (?:llames|llame)\b", "don't call her"), (r"\bno l[oe] (?:llames|llame)\b", "don't call him"),
    (r"\bno (?:vayas|vaya|vayan)\b", "don't go"), (r"\bno (?:prendas|prenda|enciendas|encienda)\b", "don't turn on"),
    (r"\bno (?:apagues|apague)\b", "don't turn off"), (r"\btodav[ií]a no\b", "not yet"), (r"\btodav[ií]a\b", "yet"),
    (r"\bno (?:cuelgues|cuelgue)\b", "don't hang up"),
    (r"\b(?:llámala|llamala|llámela|llamela)\b", "call her"), (r"\b(?:llámalo|llamalo|llámelo|llamelo)\b", "call him"),
    (_COME + r"\s+(?:aquí|aqui|acá|aca)\b", "come here"), (_COME + r"\s+al\b", "come to the"),
    (_COME + r"\s+a\b", "come to"),
    (r"^(?:" + _URGING + r"|oye|mira|bueno|ay)\b[\s,!.]*", ""), (r"\b" + _URGING + r"(?: pues)?\b", "quickly"),
    (r"\bpero\b", "but"), (r"\bgracias\b", "thank you"), (r"\b(?:la vecina|el vecino)\b", "the neighbour"),
    (r"\bmi hija\b", "my daughter"), (r"\bmi hijo\b", "my son"), (r"\b(?:el doctor|la doctora)\b", "the doctor"),
    (r"\bmañana\b", "tomorrow"), (r"\bm[aá]s tarde\b", "later"),
    (r"\bahora no\b", "not now"), (r"\bahora mismo\b", "right now"),
    (r"\by\s+(?=(?:" + _VERB + r")\b)", "and "),  # "… y llama a Ben" (before the verb is in English)
    (_GO + r"\s+al\b", "go to the"), (_GO + r"\s+a\b", "go to"),
    (_BACK + r"\s+al\b", "go back to the"), (_BACK + r"\s+a\b", "go back to"),
    (_CALL + r"\s+(?:a|al)\b(?=\s+\w)", "call"),  # "llama a Ben": the a is Spanish's, before a person
    (_ON + r"\b" + _ARTICLE, "turn on the"), (_OFF + r"\b" + _ARTICLE, "turn off the"), (_HANG_UP + r"\b", "hang up"),
    (r"\by\s+(?:después|despues|luego|entonces)\b", "and then"),
    (r"\b(?:después|despues|luego)\s+al\b", "then to the"), (r"\b(?:después|despues|luego)\b", "then"),
    (r"\bprimero\b", "first"), (r"\bpor favor\b", "please"),
    (r"\bun momentito\b|\brapidito\b", "quickly"),  # "go to the bathroom un momentito": a moment's errand
))


def said_in_spanish(text: str) -> bool:
    """A Spanish request or order word was said (`_ANY_SPANISH`)."""
    return bool(_ANY_SPANISH.search(text))


def from_spanish(text: str) -> str:
    """`text` with its Spanish requests, order words and courtesy put in English, and its rooms where
    a Spanish request or order word was said."""
    spanish = said_in_spanish(text)
    text = rewrite(text, _SPANISH)
    if not spanish:
        return text
    text = _YA.sub("now", text)  # "ya terminamos": Spanish's "now", not texting's "you"
    return _ROOM.sub(lambda m: (m.group(1) or "the ") + _ROOMS[m.group(2).lower()], text)
