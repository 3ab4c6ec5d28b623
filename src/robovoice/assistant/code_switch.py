"""Words of another language said inside English speech, in English, before the reading (the
turns of a dialect of English: `dialects`).

A home-help mixes in her Spanish ("prende el projector", "ve a la cocina primero": `spanish`), an
Indian family its Hindi ("projector band karo"). Only requests, order words and the names of rooms
are put in English, each written so it cannot be an English word. Everything else is left as said:
the model reads the person's own words, only the reading reads these.
"""

from __future__ import annotations

import re

from robovoice.assistant.afrikaans import from_afrikaans
from robovoice.assistant.arabic import from_arabic
from robovoice.assistant.creole import from_creole
from robovoice.assistant.dialects import as_standard, rewrite, rules
from robovoice.assistant.french import from_french
from robovoice.assistant.german_dutch import from_german_dutch
from robovoice.assistant.hindi import from_hindi
from robovoice.assistant.indonesian_thai import from_indonesian_thai
from robovoice.assistant.italian_greek import from_italian_greek
from robovoice.assistant.nepali import from_nepali
from robovoice.assistant.nordic import from_nordic
from robovoice.assistant.persian import from_persian
from robovoice.assistant.pidgin import from_pidgin
from robovoice.assistant.portuguese import from_portuguese
from robovoice.assistant.russian_turkish import from_russian_turkish
from robovoice.assistant.spanish import from_spanish, said_in_spanish
from robovoice.assistant.swahili import from_swahili
from robovoice.assistant.tagalog import from_tagalog
from robovoice.assistant.tamil_malayalam import from_tamil_malayalam
from robovoice.assistant.topic_first import from_topic_first
from robovoice.assistant.vietnamese_japanese import from_vietnamese_japanese

# Hindi's "switch off" and "switch on", said after the thing in Indian English (text test v68)
_HINDI_DO = r"\s+(?:karo|kar do|kar de|kardo|karde|kijiye|kar dijiye|kar dena)\b"
_HINDI_OFF = re.compile(r"\b(?:band|bandh|bund)" + _HINDI_DO, re.IGNORECASE)
_HINDI_ON = re.compile(r"\b(?:chalu|chaalu|on|start)" + _HINDI_DO, re.IGNORECASE)

# please and thank you as a carer from Poland, Romania or Ukraine says them inside English (text test v98:
# "Kitchen, proszę." was talk), and Mandarin and Cantonese ones (text test v99: "qing go to the bedroom",
# "mh goi come to the kitchen"); the words are no English word, so nothing else is read into them
_COURTESY = rules((
    (r"\b(?:prosz[eę](?: bardzo)?|v[ăa] rog|te rog|qing|q[iǐ]ng|mh? goi|唔該|请|請)\b"
     r"|(?<!\w)(?:будь ласка|пожалуйста|прошу)(?!\w)", "please"),
    (r"\b(?:dzi[eę]kuj[eę](?: bardzo)?|mul[țt]umesc|xie ?xie|do ?je|dor ?je|多謝|谢谢)\b"
     r"|(?<!\w)(?:дякую|спасибо)(?!\w)", "thank you"),
    (r"\b(?:kuai (?:yi )?dian|faai di)\b", "quickly"), (r"\bpole,? pole\b", "slowly"),  # (Swahili, text v132)
    (r"\s*,?\s*\b(?:hao ma|hou m hou|hai mai|hai m hai|ho ma)\b(?=\s*[?.!]|$)", ""),  # tags: ok?, right?
    # Cantonese "no need" and "in a while" (text test v115: "Go charge? Mh sai, …" went to charge)
    (r"\b(?:mh? sai|唔使)\b", "no need"), (r"\b(?:yat (?:j|z)an sin|dang (?:yat )?(?:j|z)an|一陣先|等陣)\b", "later"),
    (r"\b(?:xiao )?jiqiren\b", "robot"),
    # Korean (text test v105): a name called ("Anna-ya") is the name (not "Clara-ssi": the honorific is
    # part of the name the model passes on, and the robot's contacts read it); please, thank you, quickly
    (r"\b([A-Z][a-z]{2,})-(?:ya|ah)\b", r"\1"), (r"\bjebal\b", "please"),
    (r"\b(?:kamsahamnida|gamsahamnida|gomawo(?:yo)?|komawo(?:yo)?)\b", "thank you"),
    (r"\bppalli(?: ppalli)?\b", "quickly"),
))


def _other_languages(text: str) -> str:
    """`text` with its Tagalog, Hindi, Urdu, Punjabi, Swahili, Pidgin, Afrikaans, French, Portuguese, Italian,
    Greek, Arabic, German, Dutch, Russian, Turkish, Vietnamese, Japanese, Persian, Dari, Indonesian, Malay,
    Thai, Tamil, Malayalam, Creole and Nepali put in English, and the Nordic languages' turns as English says them."""
    # (Tamil first: Tagalog drops its "po", which Tamil's "Kitchen-ku po" needs)
    text = from_tagalog(from_tamil_malayalam(from_nepali(text)))
    text = from_french(from_creole(from_afrikaans(from_pidgin(from_swahili(from_hindi(text))))))
    text = from_german_dutch(from_arabic(from_italian_greek(from_portuguese(text))))
    text = from_indonesian_thai(from_persian(from_vietnamese_japanese(from_russian_turkish(text))))
    return from_nordic(text)


def translated(text: str) -> bool:
    """Whether `text` asks something in Tagalog, Hindi, Urdu, Punjabi, Swahili, Pidgin, Afrikaans, French,
    Portuguese, Italian, Greek, Arabic, German, Dutch, Russian, Turkish, Vietnamese, Japanese, Persian, Indonesian,
    Malay, Thai, Tamil, Malayalam, Creole, Nepali or Spanish words that `in_english` puts in English (a dialect of
    English is not another language)."""
    return _other_languages(text) != text or said_in_spanish(text)


def in_english(text: str) -> str:
    """`text` with the requests, order words and rooms said in Tagalog, Hindi or Spanish put in English,
    a thing said before what to do with it in English's order (`topic_first`), and a dialect's turns
    said as standard English says them (`dialects.as_standard`)."""
    text = rewrite(_other_languages(text), _COURTESY)
    text = from_topic_first(_HINDI_OFF.sub("off", _HINDI_ON.sub("on", text)))  # "Light band karo": off
    return from_spanish(as_standard(text))
