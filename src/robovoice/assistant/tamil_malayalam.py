"""Tamil and Malayalam said inside English, as grandparents, home nurses and their children in
Chennai, Kerala and the Tamil diaspora say it: a place or a person with the case ending that says
where to ("Kitchen-ku po", "Bedroom-ilekku po": go to the kitchen, the bedroom), a video call
"put" to somebody ("Doctor Weber-ku oru video call podu"), "appuram" (then), "ippo" (now),
"venda" (no need), and the kin words a person is called by ("…, mone", "…, kanna") put in English,
for the reading only (text test v121: all three of those were talk, and "Cut this call, mone, then
…" read "mone" as a step).

Nothing is rewritten unless a word only these languages have was said (`_MARKER`): "po", "vaa" and
the case endings only after a hyphen or with their verb, a kin word only where it ends a clause or
stands alone between commas. "Anna" (elder brother in Tamil) is never dropped: it is a contact.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_MARKER = re.compile(r"-(?:ku|kku|ukku|ilekku|lekku|kk)\b|\b(?:po|poo|pongo|poyi|vaa|vaanga|vaa da|podu|pannu"
                     r"|pannunga|panniru|cheyyu|appuram|apram|aprom|athukku appuram|ippo|ippove|ippol|ippozhu"
                     r"|venda|vendam|vendaam|mone|mole|kanna|kutty|chetta|chechi|machan|thambi|aiyo|ayyo|aiyyo"
                     r"|seri|naale|nale|konjam|paati|thatha|ammachi|appachan|illa|ille|oru)\b", re.IGNORECASE)

_END = r"(?=\s*(?:[,.!?;\u2026]|$))"  # where a clause ends
# where to: a place said with its ending ("living room-ku", "bedroom-ilekku")
_TO = r"((?:living room|front door|charging dock|\w+))-(?:ku|kku|ukku|ilekku|lekku|kk)"
_GO = r"(?:po|poo|pongo|poyi|po da|po di|pokku)"
_COME = r"(?:vaa|vaanga|va|vaa da|vaa di)"
_DO = r"(?:podu|pannu|pannunga|panniru|cheyyu|cheyy|adi|adikku|edu)"

_GO_TO = re.compile(_TO + r"\s+(?:" + _GO + r"|(" + _COME + r"))\b", re.IGNORECASE)

_RULES = rules((
    # a call "put" to somebody: "Doctor Weber-ku oru video call podu"
    (r"((?:(?:doctor|dr\.?) )?(?-i:[A-Z])[a-z]+)-(?:ku|kku|ukku)\s+(?:oru\s+)?((?:video )?call|phone)\s+" + _DO
     + r"\b", r"\2 \1"),
    (r"\b(on|off)\s+" + _DO + r"\b", r"\1"),  # "projector on pannu"
    (r"\b(?:athukku appuram|appuram|apram|aprom)\b", "then"), (r"\b(?:ippove|ippo|ippol|ippozhu)\b", "now"),
    (r"\b(?:venda|vendam|vendaam)\b", "no need"), (r"\b(?:naale|nale)\b", "tomorrow"),
    (r"^(?:(?:aiyo|ayyo|aiyyo|enna|seri)\b[\s,!.\u2026]*)+", ""),
    (r"\boru\s+(?=\w)", "a "),
    # the kin words a person is called by, where they end a clause or stand alone between commas
    (r"[\s,]*\b(?:mone|mole|kanna|kutty|chetta|chechi|machan|thambi|da|di|ma|pa)\b" + _END, ""),
))


def from_tamil_malayalam(text: str) -> str:
    """`text` with its Tamil and Malayalam put in English; unchanged where no word only they have was said."""
    if not _MARKER.search(text):
        return text
    text = _GO_TO.sub(lambda m: f"{'come' if m.group(2) else 'go'} to the {m.group(1).lower()}", text)
    return rewrite_where(_MARKER, text, _RULES)
