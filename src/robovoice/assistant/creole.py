"""Haitian and French-Antillean Creole (Kreyòl, Martinique's and Guadeloupe's Kréyòl) said
inside English, for the reading only (text test v126: "Eske you could ring Dr. Weber?",
"Projector la, switch it off, épi go charge yourself" and "come in the living room with me,
doudou" were talk or half done).

A Creole speaker opens a question with "eske" (est-ce que), joins steps with "épi" (and then),
puts the article after the noun ("projector la": the projector), marks what is going on with
"ka" ("I ka watch"), and names the person spoken to with an endearment at the end. Nothing is
rewritten unless a word only Creole has was said (`_MARKER`).
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_MARKER = re.compile(r"\b(?:[eè]ske|[ée]pi|apr[eèé] sa|answit|ansuit|bondye|mezanmi|gade|doudou|ch[eèé]ri|cheri|"
                     r"soupl[eéè]|silvoupl[eè]|sil vou pl[eè]|tanpri|m[eè]si|kounye a|konnya|tousuit|pita|demen|"
                     r"rele|limen|etenn|f[eè]men|annou|an nou|kwizin|lakwizin|chanm|twal[eè]t|p[oò]t la|"
                     r"(?:i|me|mwen|li|nou|ou) ka|pitit)\b", re.IGNORECASE)
_HOUSE = r"(projector|kitchen|bedroom|bathroom|hallway|living room|front door|door|dock|charger|call|screen|tv)"
_VERB = r"(?:call|ring|go|come|switch|turn|put|drive|move|hang|end|start)"

_RULES = rules((
    (r"\bsoupl[eéè]\b|\bsilvoupl[eè]\b|\bsil vou pl[eè]\b|\btanpri\b", "please"),
    (r"\bm[eè]si(?: anpil)?\b", "thank you"),
    # openers: "Bondye, …", "Gade li!" (look!), "Mezanmi, …"; a question's "eske" (est-ce que)
    (r"(^|[.!?,;\u2026]\s*)(?:(?:papa )?bondye|mezanmi|gade(?: li)?|woy)\b[\s,!.]*", r"\1"),
    (r"(^|[.!?,;\u2026]\s*)[eè]ske\s+(?:ou ka\s+)?", r"\1"),
    # an endearment naming the person spoken to, said at a clause's end
    (r"\s*,?\s*\b(?:doudou|ch[eèé]ri[e]?|cheri[e]?|ch[eè]|pitit(?: mwen)?|cocotte)\b(?=\s*(?:[,.!?\u2026]|$))", ""),
    # order words: "épi" (and), "apre sa" (after that)
    (r"(?:\band\s+)?\b(?:[ée]pi|apr[eèé] sa|answit|ansuit)\b", "and then"),
    # the article after the noun: "projector la" is the projector
    (r"\b((?:the|my|your|that|this) (?:\w+ )?)" + _HOUSE + r"\s+la\b", r"\1\2"),
    (r"\b" + _HOUSE + r"\s+la\b", r"the \1"), (r"\b(robot)\s+la\b", r"\1"),  # "Robot la, …": the robot spoken to
    # "I ka watch": what is going on
    (r"\b(i|me|mwen|li|nou|ou)\s+ka\s+(?=[a-z])", r"\1 "),
    # not, not now, later, tomorrow, now
    (r"\bpa\s+(?=" + _VERB + r"\b)", "don't "), (r"\bpa (?:kounye a|konnya|tousuit)\b", "not now"),
    (r"\b(?:kounye a|konnya|tousuit)\b", "now"), (r"\bpita\b", "later"), (r"\bdemen\b", "tomorrow"),
    (r"\b(?:annou|an nou)\b", "let's"),
    # verbs and rooms
    (r"\brele\b", "call"), (r"\blimen\b", "switch on"), (r"\b(?:etenn|f[eè]men)\b", "switch off"),
    (r"\b(?:the |la)?kwizin\b|\blakwizin\b", "the kitchen"), (r"\b(?:the )?chanm\b", "the bedroom"),
    (r"\b(?:the )?twal[eè]t\b", "the bathroom"), (r"\bp[oò]t la\b", "the front door"),
))


def from_creole(text: str) -> str:
    """`text` with its Creole requests, order words and particles put in English."""
    return rewrite_where(_MARKER, text, _RULES)
