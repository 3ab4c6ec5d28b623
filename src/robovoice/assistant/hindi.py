"""Hindi, Urdu and Punjabi, written in Latin letters inside English speech: the requests, order
words, negations and rooms put in English, for the reading only (text test v82: "kitchen tak jao
zara", "Pehle projector chalao, phir Anna ko video call milao", "Ruk ja, ruk ja! … wapas kitchen
aa ja" were talk; "Call na kaatna beta" started a call).

Hindustani puts the verb last ("Anna ko call karo": Anna-to call do), so each rule reads the
thing, then the verb, and writes the English request verb first. A negation ("mat", "na",
"nahin") said before a verb makes its clause "don't …"; "… sakte ho?" makes it "can you …?".
Nothing is rewritten unless a word only Hindustani has was said (`_MARKER`): "to", "par", "me"
and "bus" are English words too. Gujarati shares most of it; its postpositions ("kitchen ma jao":
in, "Ben ne video call karo": to), "jaine" (having gone), "ubho re" (stay) and "saheb" are read
too (text test v132).
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite, rules

_MARKER = re.compile(r"\b(?:karo|kardo|kar\s+(?:do|de|dein|dijiye|dena|lo)|karna|karein|kijiye|jao|jaao|jaiye|"
                     r"chalao|chala\s+(?:do|de|dein)|chalo|milao|mila\s+(?:do|de|dein)|lagao|laga\s+(?:do|de|dein)|"
                     r"bulao|ruko|ruk\s+ja\w*|pehle|pahle|pehlan|phir|uske|iske|nahin|nahi|zara|kya|hai|"
                     r"hain|aao|aaja|aa\s+ja|wapas|vapas|abhi|khatam|kaat\w*|bujha\w*|chalu|puttar|"
                     r"wahan|udhar|idhar|sakte|sakti|sakta|sakda|sakdi|sakde|shaam|chal|othon|uthon|jaake|dekho|karne|tashreef|"
                     r"farmaiye|mudiye|rukiye|jaldi|milaiye|lagaiye|bulaiye|chalaiye|dijiye|jaine|aavjo|saheb|ubho)\b",
                     re.IGNORECASE)
# an infinitive said with "hai" is a need ("mujhe bathroom jaana hai": I have to go), a "raha" an
# ongoing thing ("woh ghar ja rahi hai"): neither asks the robot
_NOT_ASKED = r"(?!\s+(?:hai|hain|tha|thi|hoga|hogi|padega|padegi|chahiye|raha|rahi|rahe|chuka|chuki|chuke))"


def _asks(forms: str) -> str:
    """A verb's forms, unless a need or a goings-on follows (`_NOT_ASKED`)."""
    return "(?:" + forms + ")" + _NOT_ASKED


_GIVE = r"(?:\s+(?:do|de|dein|den|dijiye|dijie|dena|diyo|lo|lein|na))?"
_DO = _asks(r"karo|kardo|karde|karna|karein|karen|kijiye|kari|karin|kareen|farmaiye|farmayen|farmaaiye|kar" + _GIVE)
# what follows the thing before the verb: a postposition, "bhi" (too), "ek" (a)
_POST = (r"(?:\s+(?:ko|nu|noo|se|tak|mein|me|main|vich|wich|pe|par|te|wal|val|ki\s+taraf|ke\s+paas|bhi|ek|zara|"
         r"ma|maa|ne|sudhi|"  # Gujarati
         r"jaldi|abhi|turant|fauran|please))*")
_PLACE = (r"((?:the\s+)?(?:living room|front door|charging dock|drawing room|"
          r"(?!(?:aa|ja|jaa|chale|chala|chali|wapas|vapas|wahan|yahan|udhar|idhar|and|the|to|go|come|then|arre|"
          r"arey|oye|haan|yeh|woh)\b)(?<!['\u2019])[a-z]{3,}))")
# someone to call: a title and a name, or a pronoun ("usko": him, her)
# (what is said of them before is left out: "saath wali Clara", the Clara next door; "meri beti Anna")
_WHO = (r"(?:(?:saath|bagal|padosi|padosan|meri|mera|mere|apni|apne|apna|wali|wala|vali|vala|beti|beta)\s+)*"
        r"((?:(?:doctor|dr\.?|uncle|aunty|auntie|nani|dadi|nana|dada|didi|bhaiya|chacha|chachi|mama|mami|bua|"
        r"masi|mausi|phuphi)\s+)?(?!(?:ko|nu|se|bhi|ji|jee)\b)\w+(?:-(?:ben|behn|bhai|ji))?)"
        r"(?:\s+(?:sahib|saab|sahab|saheb|ji|jee|aunty|auntie|uncle|bhaiya|bhai|didi|di|beta|beti|bitiya))*")
_CALL_NOUN = r"(?:video\s+wala\s+phone|video\s+call|video|phone|call|ring|dial)(?:\s+(?:pe|par))?"
_CONNECT = _asks(r"milao|mila" + _GIVE + r"|milana|milaiye|lagao|laga" + _GIVE + r"|lagana|lagaiye|bulao|bula" + _GIVE +
                 r"|bulana|bulaiye|la" + _GIVE)
_ON = _asks(r"chalao|chala" + _GIVE + r"|chalana|chalaiye|lagao|laga" + _GIVE + r"|lagana|jalao|jala" + _GIVE +
            r"|kholo|khol" + _GIVE + r"|(?:chalu|chaalu|on|start|roshan)\s+" + _DO)
_OFF = _asks(r"bujhao|bujha" + _GIVE + r"|(?:band|bandh|bund|off)\s+" + _DO + r"|hatao|hata" + _GIVE)
# ("call end karo": English's verb with Hindi's "do", audio test v75)
_END = _asks(r"khatam\s+" + _DO + r"|kaato|kato|kaat" + _GIVE + r"|kaatna|katna|(?:cut|end)\s+" + _DO
             + r"|band\s+" + _DO + r"|rakh" + _GIVE + r"|rakho")
# (Urdu's courtesy: "tashreef le jaiye", take your honoured self there; "ki taraf mudiye": turn towards)
_GO = _asks(r"(?:chale|chala|chali)\s+(?:jao|ja|jaa|jana|jaana)|tashreef\s+le\s+(?:jaiye|jaaiye|jayen|chaliye|chalein)|"
            r"jao|jaao|jaiye|jaaiye|jana|jaana|ja|jaa|chalo|chaliye|chal|mudiye|mudo|mud\s+jao|ho\s+aaiye|ho\s+aao")
_COME = _asks(r"aao|aaiye|aa\s+jao|aa\s+jana|aa\s+ja|aaja|aajao|aa\s+jaiye|aana|tashreef\s+(?:laiye|le\s+aaiye)|"
              r"aa(?=\s*(?:[,.!?]|$|\s+(?:jaldi|zara|na)\b))")
_VERB_WORD = r"(?:\w+(?:o|na|iye|ein|en|ao)|kar|ja|jaa|aa|chal|ruk|la)\b"

_RULES = rules((
    # "… sakte ho?": can you …? (the verb's stem, said as an order after "can you")
    (r"(^|[.!?,;]\s*)([^.!?,;]*?)\b(\w+)\s+(?:sakte|sakti|sakta|sakoge|sakogi|sakenge|sakda|sakdi|sakde)\b"
     r"(?:\s+(?:ho|hain|hai|hoon|hun))?(?:\s+(?:tum|aap))?(?:\s+kya)?", r"\1can you \2\3o"),
    (r"\b(?:kya|kyaa)\s+(?:tum|aap)\b", ""), (r"(^|[.!?,;]\s*)kya\b", r"\1"),
    # "A karne se pehle, B": before you A, B; "A karne ke baad, B": after you A, B (the verb's stem and "o")
    (r"(^|[.!?,;]\s*)([^.!?,;]+?)\s+(\w+?)ne\s+se\s+(?:pehle|pahle|pehlan)\b,?", r"\1before you \2 \3o,"),
    (r"(^|[.!?,;]\s*)([^.!?,;]+?)\s+(\w+?)ne\s+ke\s+baad\b,?", r"\1after you \2 \3o,"),
    # taken back: "… nahi, ruko, rehne do" (no, wait, leave it)
    (r"(^|[.!?,;\u2026]\s*)(?:nahi|nahin|nai|na)\s*,\s*(?:ruko|ruk\s+jao|ruk)\b", r"\1no, wait"),
    (r"\b(?:rehne\s+(?:do|de|dijiye)|chhodo|chhod\s+(?:do|de)|jaane\s+(?:do|de)|koi\s+baat\s+nahi)\b", "leave it"),
    (r"(^|[.!?,;\u2026]\s*)(?:nahi|nahin|nai)\b(?=\s*[,.!?\u2026])", r"\1no"),
    (r"\b(?:wahan|wahaan|vahan)\s+(?:jaake|ja\s+ke|jaa\s+ke|jakar)\b", "once you get there,"),
    (r"\b(?:te\s+|aur\s+)?(?:othon|uthon|wahan\s+se)\b", "then"), (r"\b(?:othe|uthe)\b", "there"),
    # "front door pe jaake dekho": go to the front door and look
    (r"\b" + _PLACE + _POST + r"\s+(?:jaake|jaa\s+ke|ja\s+ke|jakar|jaa\s+kar|jake|jaine|jai\s+ne)\b",
     r"go to the \1 and"),
    (r"\b(?:ubho|ubha|ubhi)\s+(?:re|raho|rahe|rejo)\b", "wait"), (r"\baavjo\b", "bye"),  # Gujarati
    (r"\b(projector|tv)\s+(?:bandh|band)\b(?!\s+\w)", r"\1 off"), (r"\b(projector|tv)\s+chalu\b(?!\s+\w)", r"\1 on"),
    (r"\b" + _PLACE + _POST + r"\s+check\s+" + _DO + r"\b", r"go and check the \1"),  # "front door check karo"
    (r"\bdekho\b(?=\s*[,!])", "look"),  # "Arre dekho, …": look, (not an errand)
    (r"\b(?:dekho|dekhna|dekh\s+lo|check\s+karo)\b", "check"),
    # "aur sab ho jaye toh …": and once that's done, …
    (r"\b(?:aur\s+)?(?:sab|yeh|ye|woh)?\s*(?:ho\s+jaye|ho\s+jaaye|ho\s+jaane\s+ke\s+baad)\s+(?:toh|to|tab)?\b",
     " and once that's done,"),
    # "Udhar nahin" (not there), "abhi nahin" (not now)
    (r"\b(?:udhar|wahan|wahaan|idhar|yahan)\s+(?:nahin|nahi|nai)\b", "not there"),
    (r"\babhi\s+(?:nahin|nahi|nai)\b", "not now"),
    # a negation before the verb: the clause is "don't …" ("Call na kaatna", "Anna ko call mat karna")
    (r"(^|[.!?,;]\s*|\b(?:aur|phir|par|lekin)\s+)([^.!?,;]*?)\b(?:mat|na|nahin|nahi|nai)\s+"
     r"(?=(?:\w+\s+)?" + _VERB_WORD + r")", r"\1don't \2"),
    # the verb, then its negation: "Rukiye mat, chalte rahiye" (don't stop, keep going)
    (r"(^|[.!?,;]\s*)([^.!?,;]*?)\b(" + _VERB_WORD + r")\s+(?:mat|nahin|nahi)\b(?=\s*[,.!?;]|$)", r"\1\2don't \3"),
    (r"\b(?:chalte|(?:aage\s+)?badhte)\s+(?:rahiye|raho|rahna)\b", "keep going"),
    (r"\bagar\b", "if"), (r"\b(?:aake|aa\s+ke|aakar)\b", "come and"),
    (r"\b(?:bas\s+)?pooch\s+(?:raha|rahi|rahe)\s+(?:hoon|hun|hu|tha|thi)\b", "I'm only asking"),
    (r"\b(?:ruko|ruk\s+jao|ruk\s+ja|rukiye|ruk\s+jaiye|ruk|thamo|tham\s+jao)\b", "stop"),
    # a call ended: "call khatam karo", "phone rakh do"
    (r"\b(?:yeh|ye|woh|wo|is|ab)?\s*\b(?:call|phone|guftagu|baat|baatcheet)\s+(?:ko\s+)?" + _END + r"\b",
     " end the call"),
    # a call made: "Anna ko video call milao", "Anna nu video wala phone la de", "Clara ko video pe bulao"
    (r"\b(?:us|usko|use|unko|unhe|inko)\s+" + _POST.replace("ko|", "") + r"\s*(?:" + _CALL_NOUN + r"\s+)?(?:" + _DO +
     r"|" + _CONNECT + r")\b", "call them"),
    (r"\b" + _WHO + _POST + r"\s+" + _CALL_NOUN + r"\s+(?:" + _DO + r"|" + _CONNECT + r")\b", r"call \1"),
    (r"\b" + _WHO + r"\s+(?:ko|nu)(?:\s+bhi)?\s+" + _CONNECT + r"\b", r"call \1"),
    (r"\b" + _CALL_NOUN + r"\s+(?:" + _DO + r"|" + _CONNECT + r")\s+" + _WHO + r"\s+(?:ko|nu)\b", r"call \1"),
    # the projector: "projector chalao", "projector baad mein lagana", "projector bujha do"
    (r"\b(projector|tv|it)\s+(?:ko\s+)?((?:\w+\s+){0,2}?)" + _ON + r"\b", r"turn on the \1 \2"),
    (r"\b(projector|tv|it)\s+(?:ko\s+)?((?:\w+\s+){0,2}?)" + _OFF + r"\b", r"turn off the \1 \2"),
    # charging: "charge pe lag jao", "charger pe chale jao"
    (r"\b(?:charging|charge|charger)\s+(?:pe|par|ke\s+liye)?\s*(?:(?:hone|karne)\s+)?"
     r"(?:lag\s+jao|lago|ho\s+jao|lag\s+ja|" + _DO + r"|"
     + _GO + r")\b", "go charge"),
    # going and coming: "kitchen tak jao", "wapas kitchen aa ja", "bedroom chalo"
    # "front door check karo" (check the front door), "wapas living room aake …" (come back to it and …),
    # "bathroom ki taraf ho aaiye" (go by the bathroom), "kitchen nahin" (not the kitchen)
    (r"\b(?:wapas|vapas)\s+" + _PLACE + _POST + r"\s+come and\b", r"come back to the \1 and"),
    (r"\b" + _PLACE + _POST + r"\s+come and\b", r"come to the \1 and"),
    (r"\b" + _PLACE + _POST + r"\s+ho\s+(?:aaiye|aao|aana|aaye)\b", r"go to the \1"),
    (r"\b" + _PLACE + r"\s+(?:nahin|nahi|nai)\b", r"not the \1"),
    (r"\b(?:wapas|vapas|waapas)\s+" + _PLACE + _POST + r"\s+(?:" + _GO + "|" + _COME + r")\b", r"go back to the \1"),
    (r"\b(?:apne|apni|apna)?\s*\b" + _PLACE + _POST + r"\s+(?:wapas|vapas|waapas)\s+(?:" + _GO + "|" + _COME + r")\b",
     r"go back to the \1"),
    (r"\b" + _PLACE + _POST + r"\s+" + _COME + r"\b", r"come to the \1"),
    (r"\b" + _PLACE + _POST + r"\s+" + _GO + r"\b", r"go to the \1"),
    (r"\b(?:wapas|vapas)\s+" + _GO + r"\b", "go back"), (r"\b(?:wapas|vapas)\s+" + _COME + r"\b", "come back"),
    # when you get there: "wahan pohonch ke"
    (r"\b(?:wahan|wahaan|vahan)\s+(?:pohonch|pahunch|pohanch|pahonch)\s*(?:ke|kar|kar\s+ke)\b", "once you get there,"),
    # order words and time
    (r"\b(?:phir|fir)\s+se\b", "again"),
    (r"\b(?:aur\s+|te\s+)?(?:phir|fir|pher|fer|uske\s+baad|iske\s+baad|us\s+ke\s+baad|baad\s+vich)\b", "then"),
    (r"\b(?:pehle|pahle|pehlan|pehla)\b", "first"), (r"\baur\b", "and"),
    (r"\b(?:baad\s+mein|baad\s+me|baad\s+main|thodi\s+der\s+(?:mein|baad))\b", "later"),
    (r"\baaj\s*kal\b", "these days"), (r"\bkal\b", "tomorrow"), (r"\bshaam\s+ko\b", "this evening"),
    (r"\b(?:abhi|hun|hune|ab)\b", "now"),
    (r"\bjaldi(?:\s+(?:jaldi|se))?\b", "quickly"),
    (r"\bcharge\s+(?:hone|karne)(?:\s+(?:ke\s+liye|ko))?\b", "to charge"),
    # what is left of a place's postposition ("…, phir front door pe,"), Punjabi "te" (and) opening a clause
    (r"\b(living room|front door|charging dock|kitchen|bedroom|bathroom|hallway)\s+(?:pe|par|te|tak|mein|me|wal)\b"
     r"(?=\s*(?:[,.!?]|$))", r"\1"),
    (r"(^|[.!?,;]\s*)te\s+(?=\w)", r"\1and "),
    (r"\b(?:kitchen|rasoi|rasoi\s*ghar)\s+(?=\s*(?:[,.!?]|$))", "the kitchen"),
))
_ROOMS = {"rasoi ghar": "kitchen", "rasoighar": "kitchen", "rasoi": "kitchen", "baithak": "living room",
          "drawing room": "living room", "kamre": "bedroom", "kamra": "bedroom", "ghusalkhana": "bathroom",
          "gusalkhana": "bathroom", "darwaza": "front door", "darwaze": "front door", "darwaaze": "front door",
          "charger": "charging dock", "dock": "charging dock"}
_ROOM = re.compile(r"(?<!charging )\b(" + "|".join(sorted(_ROOMS, key=len, reverse=True)) + r")\b", re.IGNORECASE)
# what a request carries that says nothing asked: particles, "beta" (child), "ji", "zara" (just)
# ("Priya beta, …" is said to Priya, and stays as said)
_PARTICLES = re.compile(r"(\b(?-i:[A-Z])\w*)?\s*\b(?:zara|ji|jee|beta|puttar|yaar|bhai|bhaiya|na|toh|bhi|sahib|saab|"
                        r"arre|"
                        r"arey|oye|suno|haan|miyan|seedha|sidha|"
                        r"please\s+na)\b(?=\s*(?:[,.!?]|$|\s))", re.IGNORECASE)


def _particle(m: re.Match[str]) -> str:
    """Nothing for a particle, unless it follows a name that opens a clause ("Priya beta, …"): then
    it says who is spoken to."""
    name = m.group(1)
    opens = name is not None and re.search(r"(?:^|[.!?,;]\s*)$", m.string[:m.start(1)]) is not None
    return m.group(0) if opens and name.lower() not in _NOT_NAMES else (name or "")


_NOT_NAMES = frozenset({"arre", "arey", "acha", "accha", "achha", "haan", "chalo", "please", "suno", "oye", "bas",
                        "then",
                        "first", "quickly", "now"})


def from_hindi(text: str) -> str:
    """`text` with the Hindi, Urdu or Punjabi of a request put in English (unchanged without any)."""
    if not _MARKER.search(text):
        return text
    text = _ROOM.sub(lambda m: _ROOMS[m.group(1).lower()], text)
    text = _PARTICLES.sub(_particle, rewrite(text, _RULES))
    text = re.sub(r"\s+([,.!?])", r"\1", re.sub(r"\bthe the\b", "the", re.sub(r"  +", " ", text)))
    return re.sub(r"^[\s,]+|(?<=[.!?])[\s,]+(?=\w)", lambda m: "" if m.start() == 0 else " ", text).strip()
