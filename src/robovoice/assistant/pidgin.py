"""Nigerian and Ghanaian Pidgin (and the Igbo, Yoruba, Hausa and Twi words said inside it): the
requests, negations, questions and order words put in English, for the reading only (text
test v88: "Off that projector light", "Oya end this call", "Waka go hallway first", "Carry
yourself enter kitchen", "Kashe the projector" were talk, or a step was lost).

Pidgin says a request as English does, with its own verbs and particles: "off/on" are verbs
("off am": switch it off), "am" is it/him/her after a verb, "make you …" and "make we …" ask
(you should, let's), "no go …" forbids, "you fit …?" asks what the robot can do, "oya",
"ngwa", "ehen" open a request, "o", "jare", "sef" end one. Nothing is rewritten unless a
word only Pidgin has was said (`_MARKER`): "dey", "don", "make" and "off" are English too.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_MARKER = re.compile(r"\b(?:abeg|oya|ngwa|ehen|ehn|wetin|abi|sebi|shey|dey|una|wahala|comot|waka|sabi|pikin"
                     r"|chale|chaley|biko|jare|sef|kashe|kunna|make (?:you|we)|no be|sharp sharp|e don"
                     r"|don (?=come|reach|finish|do|go|tire)"
                     r"|(?:off|on|do|call|ring|stop|end|leave|forget|kashe|kunna|cut) am"
                     r"|carry (?:yourself|your body) (?:go|enter)|i beg,? (?=go|come|on|off|call|ring|end|stop)"
                     r"|mepaakyew|mepa wo kyew|medaase|ejo|ejoor|nne|nna|haba)\b", re.IGNORECASE)

_ROOMS = (r"(?:the\s+)?(?:kitchen|bedroom|bathroom|hallway|living room|parlour|parlor|sitting room|front door"
          r"|charging dock|charger|dock|toilet|corridor)\b")
# where a clause, and so a request, starts
_START = r"(^|[.!?,;\u2026]\s*|\b(?:please|abeg|and|then|now|first|so|from there)\s+)"
_VERBS = (r"(?:go|come|call|ring|off|on|switch|turn|stop|end|cut|comot|carry|check|enter|wait|hold|move|drive|bring"
          r"|show|play|put|return|charge|take|help|tell|find|look|do|kashe|kunna)\b")

_RULES = rules((
    # openers and tags that say nothing asked: "oya", "ngwa" (Igbo: come on), "ehen", "chale"
    # (Ghana: friend); "biko", "ejo" (Igbo, Yoruba) and "mepaakyew" (Twi) are please
    (r"\b(?:biko|ejo(?:or)?|mepaakyew|mepa wo kyew)\b", "please"), (r"\bmedaase\b", "thank you"),
    (r"\b(?:oya|ngwa|ehen|ehn|chale|chaley|haba)\b[\s,!.]*", ""),
    (_START + r"i beg,?\s+(?=" + _VERBS + ")", r"\1please "),  # "I beg, on the projector": please
    (r"\s*,?\s*\b(?:(?-i:o+)|jare|sef|abi|(?-i:nne)|(?-i:nna))\b(?=\s*(?:[,.!?\u2026]|$))", ""),
    (r"\b(?:sharp sharp|quick quick|fast fast)\b", "quickly"), (r"\bnow now\b", "right now"),
    # "make you no …": don't; "make you …": a request; "make we …": let's
    (_START + r"make (?:you|una) no\s+", r"\1don't "), (_START + r"make (?:you|una)\s+(?=" + _VERBS + ")", r"\1"),
    (r"\bmake we\b", "let's"),
    (_START + r"(?:no|no dey)\s+(?=" + _VERBS + ")", r"\1don't "),  # "no go kitchen": don't (not "no, go …")
    (r"\bno be now\b", "not now"), (r"\bno be today\b", "not today"),
    # "you fit …?": can you …? "you sabi …?": do you know how to …?
    (_START + r"(?:you|una) fit\b", r"\1can you"),
    (_START + r"(?:you|una) sabi(?:\s+how to)?\b", r"\1do you know how to"),
    # verbs: "off/on" before the thing, Hausa's "kashe" (switch off) and "kunna" (switch on), "am" after them
    (r"\b(?:kashe)\b", "off"), (r"\b(?:kunna)\b", "on"),
    (r"\b(call|ring)\s+am\b", r"\1 them"), (r"\b(off|on|do|stop|end|leave|forget|cut)\s+am\b", r"\1 it"),
    (_START + r"(off|on)\s+(?=(?:(?:the|that|this|dat|dis|my|your)\s+)?(?:projector|light|screen|tv|telly|it)\b)",
     r"\1switch \2 "),
    (r"\b(?:carry|take)\s+(?:yourself|your body)\b", "go"), (r"\bwaka\b", "go"), (r"\bcomot\b", "leave"),
    (r"\bgo\s+(?:go|enter|waka)\b", "go"), (_START + r"(?:enter|reach|pass)\s+(?=" + _ROOMS + ")", r"\1go to "),
    (r"\b(go|come|run|hurry|go back|come back)\s+(?=(?!the\b)" + _ROOMS + ")", r"\1 to the "),
    (r"\b(?:parlour|parlor)\b", "living room"),
    (r"\bwan\b", "want"), (r"\bwetin\b", "what"),
))


def from_pidgin(text: str) -> str:
    """`text` with its Pidgin requests put in English; unchanged where no Pidgin word was said."""
    return rewrite_where(_MARKER, text, _RULES)
