"""Swedish, Norwegian, Danish and Finnish turns said in English, as older people there speak it,
put as English says them, for the reading only (text test v124): the particles a sentence opens
with ("Ja,", "Jo,", "Nå,", "No niin,": yes, well), thank you, and the false friends and literal
turns of phrase:

- "eventually you could …" is "could you …" (Swedish "eventuellt": possibly), not later;
- "make the projector on" is "switch it on"; "lay on the call" is "hang up" (Swedish "lägga på");
- "you shall drive to …" is asked now (Danish and Norwegian "du skal"), and so is "be so good and …";
- "then we call Anna" is "then let's call Anna"; "ring to Clara" is "ring Clara".

v124 read "No niin" as a "no", "Jo, you shall …" as said to a person called Jo, "eventually" as
later, and "you can lay on the call" as a call to make. "stop the call" is `word_finding`'s.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rules

# (not "Jo": a name too; "Jo, you shall …" is asked by its "you shall")
_OPENING = re.compile(r"^(?:(?:no niin|noniin|nå|nå ja|ja|joo|jaa|nej men)\b[\s,!.]*)+(?=\w)", re.IGNORECASE)
_RULES = rules((
    (r"\b(?:tack så mycket|tack|tusen takk|takk|kiitos paljon|kiitos|mange tak)\b", "thank you"),
    (r"\beventually,? you (could|can|might|may)\b", r"\1 you"),
    (r"\byou (could|can|might|may) eventually\b", r"\1 you"),
    (r"\bmake (?:the |your )?(projector|screen|telly|tv) (on|off)\b", r"switch the \1 \2"),
    (r"\bmake (on|off) the (projector|screen|telly|tv)\b", r"switch \1 the \2"),
    (r"\b(?:lay|put) on the (?:call|phone)\b", "hang up the call"),
    (r"\byou shall (?!not\b|never\b)(?=\w)", "please "),
    (r"\bbe so (?:good|kind) and (?=\w)", "please "),  # Swedish "var så god och …" (audio test v115)
    # (not a drive: "And now we go live to our reporter outside the front door" is the news)
    (r"\b(then|so) we (call|ring|switch|turn|make|put|end)\b", r"\1 let's \2"),
    (r"(?<!\ba )(?<!\bthe )\b(ring|phone) to (?=(?-i:[A-Z]))", r"\1 "),  # (not "a call to Ben": a noun)
))


def from_nordic(text: str) -> str:
    """`text` with its Nordic turns said as English says them."""
    text = _OPENING.sub("", text.strip())
    for pattern, english in _RULES:
        text = pattern.sub(english, text)
    return text
