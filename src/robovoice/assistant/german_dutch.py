"""German and Dutch said inside English, as German, Austrian, Swiss and Dutch speakers at home say it:
please, thank you, no, time words, the "Beamer" (a projector), "out" and "aus" for off, and a verb
said before its "then" ("call then Ben"), put in English for the reading only (text test v103:
"Beamer out." was talk; "Finish with Anna and call then Ben" rang Anna).

Nothing is rewritten unless a word only these languages have was said (`_MARKER`); "nu" (Dutch
now, Romanian no) and "also" (English too) are left as said.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite, rules

# "call then Ben", "go then to the kitchen": the verb before its "then", as German says it; the verb,
# not a noun ("end the call then go"): at the start, or after "and" or a comma
_VERB_THEN = r"(?:^|(?<=\band )|(?<=, ))(call|ring|phone|go|drive|come)\s+then\s+"
_THING = r"(?:the |that |this |your |my |de |der |den |die )?(?:beamer|projector|light|it)"
_MARKER = re.compile(r"\b(?:beamer|bitte|danke|dankeschön|genau|ach so|jawohl|nein|nee|alsjeblieft|alstublieft"
                     r"|dank je|dank u|graag|morgen|später|jetzt|sofort|langsam|gleich|tja|na ja|aus"
                     r"|" + _VERB_THEN + r")\b", re.IGNORECASE)

_RULES = rules((
    (r"\b(?:bitte(?: schön| sehr)?|alsjeblieft|alstublieft)\b", "please"),
    (r"\b(?:danke(?: schön| sehr)?|dankeschön|dank (?:je|u)(?: wel)?)\b", "thank you"),
    (r"^(?:(?:ach so|genau|jawohl|tja|na ja|so so)\b[\s,!.]*)+", ""),
    (r"\b(?:nein|nee)\b(?=\s*[,.!?]|\s*$)", "no"),
    (r"\bmorgen\b", "tomorrow"), (r"\bspäter\b", "later"), (r"\bjetzt\b", "now"), (r"\bsofort\b", "right now"),
    (r"\blangsam\b", "slowly"), (r"\bgleich\b", "in a moment"),
    (r"\b(?:de |der |den |die )?beamer\b", "the projector"),
    (r"\bthe (?:the|that|this|your|my) projector\b", "the projector"),
    # "switch the beamer out", "Beamer aus": off; "Beamer an": on
    (r"\b(switch|turn|make|put|do|set)\s+(" + _THING + r")\s+(?:out|aus)\b", r"\1 \2 off"),
    (r"\b(the projector|it)\s+(?:out|aus)\b", r"\1 off"), (r"\b(the projector)\s+an\b(?=\s*[,.!?]|\s*$)", r"\1 on"),
))


def from_german_dutch(text: str) -> str:
    """`text` with its German and Dutch put in English; unchanged where no word only they have was said."""
    if not _MARKER.search(text):
        return text
    text = re.sub(_VERB_THEN, lambda m: f"then {m.group(1).lower()} ", rewrite(text, _RULES), flags=re.IGNORECASE)
    return re.sub(r"^[\s,]+", "", text)
