"""Words of another language said inside English speech, in English, before the reading (the
turns of a dialect of English: `dialects`).

A home-help mixes in her Spanish ("prende el projector", "ve a la cocina primero"), an Indian
family its Hindi ("projector band karo"). Only requests, order words and the names of rooms
are put in English here, each written so it cannot be an English word: Spanish "llama a" (call),
not the animal; "ve" not inside "I've"; "para" (stop, but also "for") not at all. Everything
else is left as said: the model reads the person's own words, only the reading reads these.
"""

from __future__ import annotations

import re

from robovoice.assistant.afrikaans import from_afrikaans
from robovoice.assistant.dialects import as_standard, rewrite, rules
from robovoice.assistant.french import from_french
from robovoice.assistant.hindi import from_hindi
from robovoice.assistant.pidgin import from_pidgin
from robovoice.assistant.swahili import from_swahili
from robovoice.assistant.tagalog import from_tagalog

# Hindi's "switch off" and "switch on", said after the thing in Indian English (text test v68)
_HINDI_DO = r"\s+(?:karo|kar do|kar de|kardo|karde|kijiye|kar dijiye|kar dena)\b"
_HINDI_OFF = re.compile(r"\b(?:band|bandh|bund)" + _HINDI_DO, re.IGNORECASE)
_HINDI_ON = re.compile(r"\b(?:chalu|chaalu|on|start)" + _HINDI_DO, re.IGNORECASE)

# Spanish requests, in the familiar and the polite form (text test v69)
_GO = r"(?<!['\u2019])\b(?:ve|vete|vaya|vayas|vayan|váyase|vayase)"
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
# (a whole word: "very" is not "ve")
_ANY_SPANISH = re.compile("|".join(["(?:" + _VERB + r")\b", r"\b(?:después|despues|luego|primero|por favor)\b"]),
                          re.IGNORECASE)
_YA = re.compile(r"\bya\b", re.IGNORECASE)

_SPANISH = rules((
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


# please and thank you as a carer from Poland, Romania or Ukraine says them inside English (text test v98:
# "Kitchen, proszę." was talk), and Mandarin and Cantonese ones (text test v99: "qing go to the bedroom",
# "mh goi come to the kitchen"); the words are no English word, so nothing else is read into them
_COURTESY = rules((
    (r"\b(?:prosz[eę](?: bardzo)?|v[ăa] rog|te rog|qing|q[iǐ]ng|mh? goi|唔該|请|請)\b"
     r"|(?<!\w)(?:будь ласка|пожалуйста|прошу)(?!\w)", "please"),
    (r"\b(?:dzi[eę]kuj[eę](?: bardzo)?|mul[țt]umesc|xie ?xie|do ?je|dor ?je|多謝|谢谢)\b"
     r"|(?<!\w)(?:дякую|спасибо)(?!\w)", "thank you"),
    (r"\b(?:kuai (?:yi )?dian|faai di)\b", "quickly"), (r"\s*,?\s*\b(?:hao ma|hou m hou)\b(?=\s*[?.!]|$)", ""),
    (r"\b(?:xiao )?jiqiren\b", "robot"),
))


def _other_languages(text: str) -> str:
    """`text` with its Tagalog, Hindi, Urdu, Punjabi, Swahili, Pidgin, Afrikaans and French put in
    English."""
    return from_french(from_afrikaans(from_pidgin(from_swahili(from_hindi(from_tagalog(text))))))


def translated(text: str) -> bool:
    """Whether `text` asks something in Tagalog, Hindi, Urdu, Punjabi, Swahili, Pidgin, Afrikaans, French or
    Spanish words that `in_english` puts in English (a dialect of English is not another language)."""
    return _other_languages(text) != text or bool(_ANY_SPANISH.search(text))


def in_english(text: str) -> str:
    """`text` with the requests, order words and rooms said in Tagalog, Hindi or Spanish put in English,
    and a dialect's turns said as standard English says them (`dialects.as_standard`)."""
    text = rewrite(_other_languages(text), _COURTESY)
    text = as_standard(_HINDI_OFF.sub("off", _HINDI_ON.sub("on", text)))  # "Light band karo": off
    spanish = bool(_ANY_SPANISH.search(text))
    text = rewrite(text, _SPANISH)
    if not spanish:
        return text
    text = _YA.sub("now", text)  # "ya terminamos": Spanish's "now", not texting's "you"
    return _ROOM.sub(lambda m: (m.group(1) or "the ") + _ROOMS[m.group(2).lower()], text)
