"""Russian and Turkish said inside English, as older people from Russia, Ukraine, Turkey and their
families say it: openers, no, please, thank you, order and time words put in English, for the
reading only (text test v106: "Hadi, bedroom" and "Önce... yani, first kitchen" made steps of the
openers, "Nyet, nyet, not there! Hallway I said" named no place to go).

Nothing is rewritten unless a word only these languages have was said (`_MARKER`): "tak", "nu" and
"net" alone are not taken from English. "Da" and "evet" (yes) are left as said: a yes asks nothing.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_MARKER = re.compile(r"\b(?:hadi|haydi|hayde|davai|davay|dawai|yani|tamam|ladno|slushay|nyet|hay[\u0131i]r|l[üu]tfen"
                     r"|pozhalu[iy]?sta|pozhalujsta|spasibo|sa[ğg]ol|te[şs]ekk[üu]r(?:ler| ederim)?|[öÖ]nce"
                     r"|snachala|sonra|potom|[şs]imdi|seichas|seychas|sejchas|yar[\u0131i]n|zavtra|bystro|[çc]abuk"
                     r"|vsyo|vs[e\u0451]|bozhe|aman|allah allah|k[\u0131i]z[\u0131i]m|o[ğg]lum|dochka|synok"
                     r"|can[\u0131i]m)\b",
                     re.IGNORECASE)

_RULES = rules((
    (r"\b(?:nyet|hay[\u0131i]r)\b", "no"),
    (r"\b(?:l[üu]tfen|pozhalu[iy]?sta|pozhalujsta)\b", "please"),
    (r"\b(?:spasibo(?: bolshoe)?|sa[ğg]ol(?:un)?|te[şs]ekk[üu]r(?:ler| ederim)?)\b", "thank you"),
    # openers, fillers and calls, which ask nothing: "Hadi, bedroom", "Nu vsyo, bye-bye Anna", "kizim" (my girl)
    (r"^(?:(?:hadi|haydi|hayde|davai|davay|dawai|nu|tak|yani|tamam|ladno|slushay|bozhe(?: moi)?|aman|allah allah"
     r"|vsyo|vs[e\u0451])\b[\s,!.\u2026]*)+", ""),
    (r"\s*,?\s*\b(?:yani|tamam|ladno|davai|davay|hadi)\b(?=\s*(?:[,.!?\u2026]|$))", ""),
    (r"\b(?:k[\u0131i]z[\u0131i]m|o[ğg]lum|dochka|synok|can[\u0131i]m)\b", "dear"),
    # order and time words; "önce" only with its ö: "once" is English
    (r"\b(?:[öÖ]nce|snachala)\b[\s,.\u2026]*(?=first\b)", ""), (r"\b(?:[öÖ]nce|snachala)\b", "first"),
    (r"\b(?:sonra|potom)\b", "then"), (r"\b(?:[şs]imdi|seichas|seychas|sejchas)\b", "now"),
    (r"\b(?:yar[\u0131i]n|zavtra)\b", "tomorrow"), (r"\b(?:bystro|[çc]abuk)\b", "quickly"),
))


def from_russian_turkish(text: str) -> str:
    """`text` with its Russian and Turkish put in English; unchanged where no word only they have was said."""
    return rewrite_where(_MARKER, text, _RULES)
