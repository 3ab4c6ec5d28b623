"""Words of another language said inside English speech, in English, before the reading; and
turns of a dialect said as standard English says them (Singlish, Southern US, Jamaican Patois,
Hong Kong and Maltese English).

A home-help mixes in her Spanish ("prende el projector", "ve a la cocina primero"), an Indian
family its Hindi ("projector band karo"). Only requests, order words and the names of rooms
are put in English here, each written so it cannot be an English word: Spanish "llama a" (call),
not the animal; "ve" not inside "I've"; "para" (stop, but also "for") not at all. Everything
else is left as said: the model reads the person's own words, only the reading reads these.
"""

from __future__ import annotations

import re

# Hindi's "switch off" and "switch on", said after the thing in Indian English (text test v68)
_HINDI_DO = r"\s+(?:karo|kar do|kar de|kardo|karde|kijiye|kar dijiye|kar dena)\b"
_HINDI_OFF = re.compile(r"\b(?:band|bandh|bund)" + _HINDI_DO, re.IGNORECASE)
_HINDI_ON = re.compile(r"\b(?:chalu|chaalu|on|start)" + _HINDI_DO, re.IGNORECASE)

# Spanish requests, in the familiar and the polite form (text test v69)
_GO = r"(?<!['\u2019])\b(?:ve|vete|vaya|váyase|vayase)"
_BACK = r"\b(?:regresa|regrese|vuelve|vuelva)"
_CALL = r"\b(?:llama|llame|llámale|llamale|llámele|llamele)"
_ON = r"\b(?:prende|prenda|enciende|encienda)"
_OFF = r"\b(?:apaga|apague)"
_HANG_UP = r"\b(?:cuelga|cuelgue)"
_ARTICLE = r"(?:\s+(?:el|la|los|las)\b)?"
_VERB = "|".join((_GO, _BACK, _CALL, _ON, _OFF, _HANG_UP))

# rooms (and the projector) said in Spanish: an article before them is said in English too
_ROOMS = {"cocina": "kitchen", "baño": "bathroom", "bano": "bathroom", "cuarto": "bedroom",
          "recámara": "bedroom", "recamara": "bedroom", "habitación": "bedroom", "habitacion": "bedroom",
          "dormitorio": "bedroom", "sala": "living room", "pasillo": "hallway",
          "puerta de entrada": "front door", "puerta": "front door", "proyector": "projector"}
_ROOM = re.compile(r"\b(?:(the\s+)|(?:el|la)\s+)?(" + "|".join(sorted(_ROOMS, key=len, reverse=True)) + r")\b",
                   re.IGNORECASE)  # an English "the" before it is kept as said ("al" has made one)
# the rooms are put in English only where a Spanish request or order word was said: "sala" and
# "puerta" alone are not taken from an English sentence
_ANY_SPANISH = re.compile("|".join([_VERB, r"\b(?:después|despues|luego|primero|por favor)\b"]), re.IGNORECASE)
_YA = re.compile(r"\bya\b", re.IGNORECASE)

_SPANISH = tuple((re.compile(pattern, re.IGNORECASE), english) for pattern, english in (
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


# Singlish (text test v70): its particles say nothing asked ("Off the projector lah"); "X can or
# not?" is "can you X?"; "see got water on the floor or not" is "see if there is …"; "go toilet"
# is "go to the toilet"
_PARTICLE = re.compile(r"\s*,?\s*\b(?:lah|leh|lor|hor|meh|sia)\b"
                       r"|(?<=\w) (?:ah|ha|la|ar|wor|lo|mah)(?=\s*(?:[,.!?\u2026]|$))", re.IGNORECASE)
_CAN_OR_NOT = re.compile(r"(^|[.!?\u2026,]\s*)(?:you )?([^.!?\u2026,]+?),?\s+can (?:or )?(?:not|anot)\b",
                         re.IGNORECASE)
_GOT_OR_NOT = re.compile(r"\bgot ([^,.!?\u2026]+?) or not\b", re.IGNORECASE)
_GO_ROOM = re.compile(r"\b(go|come) (toilet|kitchen|bedroom|bathroom|hallway|living room)\b", re.IGNORECASE)


# Southern US (text test v71): "y'all might could call …" is "could you call …"; a dropped g
# ("quit rollin'", "actin' up") is written as said in full
_MIGHT_COULD = re.compile(r"(?:(^|[.!?,;\u2026]\s*)|\b(?:y'?all|you(?: all)?|ya) )might (could|can|would)(?: you)?\b",
                          re.IGNORECASE)  # at a clause's start, or after "you": not "I might could go"
_DROPPED_G = re.compile(r"\b([a-z]{2,}in)['\u2019](?!\w)", re.IGNORECASE)


# Jamaican Patois (text test v72): "go a di kitchen, den call Anna fi mi", "nuh go deh", "tun roun'",
# "tek yuhself go a di …", "mek we call Anna nuh". "di" only in lower case ("Di" may be a name); "den"
# not after "the", "my", "a", "our" or "your" (a den is a room)
_PATOIS = tuple((re.compile(pattern, re.IGNORECASE if flags else 0), english) for pattern, english, flags in (
    (r"\bwah gwaan\b", "hi", True), (r"\bgwaan(?: go)?\b", "go", True),  # "gwaan a di …": go on to the …
    (r"\b(go|come|get|back|run|reach)\s+a\s+(?=(?:di|de|the|yuh|your|mi|my)\b)", r"\1 to ", True),
    (r"\bdi\b", "the", False),
    (r"(?<!\bthe )(?<!\bmy )(?<!\ba )(?<!\bour )(?<!\byour )\bden\b", "then", True),
    (r"\ban['\u2019](?=\s|$)", "and", True), (r"\broun['\u2019]?(?!\w)", "round", True),
    (r"\bhol['\u2019](?=\s|,)", "hold", True), (r"\btun\b(?=\s+(?:roun|round|off|on|it|the|di)\b)", "turn", True),
    (r"\bnuh\s+(?=(?:go|call|ring|turn|tun|switch|put|come|move|drive|do|bother|mind)\b)", "don't ", True),
    (r"\s*,?\s*\bnuh\b(?=\s*(?:[,.!?\u2026]|$))", "", True),  # "… nuh": asking, said at the end
    (r"\bfi mi\b", "for me", True), (r"\bdeh\b", "there", True), (r"\bdat\b", "that", True),
    (r"\bdis\b", "this", True), (r"\btek\b", "take", True), (r"\byuhself(?: go)?\b", "yourself", True),
    (r"\byuh\b", "your", True), (r"\bmek we\b", "let's", True), (r"\bwaan\b", "want", True),
    (r"\bcyaan\b", "can't", True),
))

# Hong Kong English (text test v72): "open / close (the) projector" is switching it on or off; "add
# oil" cheers the robot on; "ar" before its name is a particle (its "la", "wor", "mah" at a clause's
# end are dropped with Singlish's)
_OPEN = re.compile(r"\b(open|close)\s+(?:the\s+)?(projector|screen)\b", re.IGNORECASE)
_CHEER = re.compile(r"\badd oil\b[\s,!.]*|\bar\b(?=\s+robot\b)", re.IGNORECASE)


# Maltese English (text test v73): "u" between a thing and a request is "and" (not texting's "you":
# "can u go …"); "pass from / through the X" is going there on the way; "ejja" (come on) and "mela"
# (so) open or close a request; "the light of the projector" is the projector
_AND_U = re.compile(r"\b(\w+)\s+u\s+(?=(?:go|come|call|ring|switch|turn|put|close|open|end|take|head|drive|get"
                    r"|stop|show|bring|finish)\b)", re.IGNORECASE)
_NOT_AND = frozenset({"can", "could", "will", "would", "do", "did", "are", "were", "if", "when", "thank", "have",
                      "should", "shall", "may", "might", "must", "love", "need", "want", "let", "as", "so", "and",
                      "or", "than", "that", "then", "once", "before", "after", "till", "until", "see", "tell"})
_PASS_FROM = re.compile(r"\bpass (?:from|through|by) (?=(?:the|my|your)\b)", re.IGNORECASE)
_MALTESE_FILLER = re.compile(r"\b(?:ejja|mela)\b[,!.]?\s*|,\s*(?:ejja|mela)\b(?=\s*[.!?]|$)", re.IGNORECASE)
_LIGHT_OF = re.compile(r"\bthe light (?:of|on) the (projector|screen)\b", re.IGNORECASE)


def _maltese(text: str) -> str:
    text = _AND_U.sub(lambda m: m.group(0) if m.group(1).lower() in _NOT_AND else f"{m.group(1)} and ", text)
    return _LIGHT_OF.sub(r"the \1", _PASS_FROM.sub("go to ", _MALTESE_FILLER.sub("", text)))


def in_english(text: str) -> str:
    """`text` with the requests, order words and rooms said in Hindi or Spanish put in English,
    and the turns of Singlish, Southern US, Jamaican Patois, Hong Kong and Maltese English said as
    English says them."""
    text = _HINDI_OFF.sub("off", _HINDI_ON.sub("on", text))  # "Projector band karo": "projector off"
    text = _GO_ROOM.sub(r"\1 to the \2", _GOT_OR_NOT.sub(r"if there is \1", _PARTICLE.sub("", text)))
    text = _CAN_OR_NOT.sub(r"\1can you \2", text)
    text = _maltese(text)
    for pattern, english in _PATOIS:  # before the dropped g: "an'" is "and", not "ang"
        text = pattern.sub(english, text)
    text = _MIGHT_COULD.sub(lambda m: f"{m.group(1) or ''}{m.group(2)} you", _DROPPED_G.sub(r"\1g", text))
    text = _OPEN.sub(lambda m: f"turn {'on' if m.group(1).lower() == 'open' else 'off'} the {m.group(2)}",
                     _CHEER.sub("", text))
    spanish = bool(_ANY_SPANISH.search(text))
    for pattern, english in _SPANISH:
        text = pattern.sub(english, text)
    if not spanish:
        return text
    text = _YA.sub("now", text)  # "ya terminamos": Spanish's "now", not texting's "you"
    return _ROOM.sub(lambda m: (m.group(1) or "the ") + _ROOMS[m.group(2).lower()], text)
