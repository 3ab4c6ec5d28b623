"""Arabic said inside English, as Egyptian, Lebanese and Iraqi families in Manchester, Dearborn and
Sydney say it (in Latin letters): please, thank you, the urging "yalla", the "ya" before whom one
speaks to, and time words put in English, for the reading only (text test v102: "To the bedroom,
yalla." was talk; "Bathroom, ya Jarvis, …" was not a request to the robot).

"Inshallah" is left as said: it is "hopefully" as often as "later, maybe", and a time word beside
it says which; only before "you can …" opening the utterance is it dropped ("Inshallah you can put
the projector on now": hopefully you will, text test v131). Nothing is rewritten unless a word only
Arabic has was said (`_MARKER`).
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import ROOM, rewrite, rules

# endearments and whom one speaks to after "ya" ("ya albi": my heart; "ya teta": grandma)
_DEAR = r"(?:albi|alby|habibi|habibti|habibty|habibte|hayati|hayatii|rouhi|roohi)"
_KIN = r"(?:ibni|binti|ammo|amo|teta|tata|jiddo|sitti)"  # ("Tata is standing there": only after "ya" a vocative)
_MARKER = re.compile(r"\b(?:yalla|yallah|yala|shukran|shokran|min fadlak|min fadlik|min fadlek|law samaht|law samahti"
                     r"|afwan|khalas|khallas|bukra|bokra|ba'?dain|ba'?dein|ba3dein|halla2|hala2|halla'?|hela2"
                     r"|shway shway|shwaya shwaya|shwayy|bsur'?a|bsor'?a|wallah|wallahi|mashallah|tayeb"
                     r"|tayyib|inshallah"
                     r"|ya " + _KIN + r"|ya (?:jarvis|robot)|" + _DEAR + r")\b", re.IGNORECASE)  # (Swahili's "ya": of)

_RULES = rules((
    (r"\b(?:min fadl(?:ak|ik|ek)|law samaht(?:i)?)\b", "please"),
    (r"\b(?:shukran|shokran)(?: (?:kteer|ktir|jazeelan|jazilan))?\b", "thank you"),
    # "ya Jarvis": the robot spoken to; "ya albi", "habibti": endearments, which ask nothing
    (r"\bya (?=(?-i:[A-Z]))", ""), (r",?\s*\b(?:ya )?" + _DEAR + r"\b|,?\s*\bya " + _KIN + r"\b", ""),
    (r"^inshallah,?\s+(?=you (?:can|could|will|would)\b)", ""),
    # "Yalla, bedroom, habibi.": off you go to the room named (text test v131)
    (r"^(?:yalla|yallah|yala)\b[\s,!.]+(?:to\s+)?(?=(?:the |my |your )?" + ROOM + r"\b)", "go to "),
    (r"^(?:(?:yalla|yallah|yala|wallah|wallahi|mashallah|tayeb|tayyib|tab|ahlan)\b[\s,!.]*)+", ""),
    (r"\b(?:yalla|yallah|yala)\b|\bbsu?o?r'?a\b", "quickly"), (r"\b(?:shway shway|shwaya shwaya)\b", "slowly"),
    (r"\b(?:bukra|bokra)\b", "tomorrow"), (r"\b(?:ba'?dain|ba'?dein|ba3dein)\b", "later"),
    (r"\b(?:halla2|hala2|halla'?|hela2)\b", "now"),
    # "…, so the projector off, khalas.": that's it, said after the request, no stop (text test v131)
    (r"\b(on|off)\s*,\s*(?:khalas|khallas)\b(?=\s*[.!]?\s*$)", r"\1"),
    (r"\b(?:khalas|khallas)\b(?=\s*(?:[,.!?]|$))", "enough"),  # "khalas!": that's it (not "khalas with …")
    (r"\b(?:wallah|wallahi|mashallah)\b", ""),
))


def from_arabic(text: str) -> str:
    """`text` with its Arabic put in English; unchanged where no word only Arabic has was said."""
    if not _MARKER.search(text):
        return text
    return re.sub(r"\s+([,.!?])", r"\1", re.sub(r"^[\s,]+", "", rewrite(text, _RULES)))
