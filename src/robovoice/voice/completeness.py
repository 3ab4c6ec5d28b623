"""Whether the words said so far form a complete request: the rule behind the shorter
end-of-turn silence (docs/voice.md, "Using the end-of-turn silence"). Pure, no model.

A request is taken as unfinished when its last words ask for more: a conjunction ("and",
"then"), an article or possessive ("the", "my"), a preposition ("to", "into"), a hesitation
("um"), a verb still missing its object ("turn", "call", "go"), or a question word on its own
("where"); also when speech-to-text marks a trailing-off (a comma, a dash or "..."). Only then
is the full silence kept; everything else may end on the shorter one. Nothing is said about
what the request means: "go to the kitchen" and "blah blah." are both complete.
"""

from __future__ import annotations

import re
from typing import Final


def _set(words: str) -> frozenset[str]:
    return frozenset(words.split())


_CONJUNCTIONS: Final = _set(
    "and or but then so because if when while until unless before after whether than nor plus also"
)
_DETERMINERS: Final = _set(
    "the a an my your his her its our their this that these those some any every each no another which "
    "what whose"
)
_PREPOSITIONS: Final = _set(
    "to into onto at in on of for from with without by about towards toward near through past over under "
    "between behind beside next across around inside outside via like as"
)
_HESITATIONS: Final = _set("um umm uh uhh er erm hmm hm ah eh mm")
# Verbs that, last, still want what they act on ("turn" on the projector, "call" whom?).
_OPEN_VERBS: Final = _set(
    "go drive move turn switch call tell show take bring set put find get give send open close start "
    "navigate head is are can could would will should let let's i'd i'm want need what's where's who's "
    "how's"
)
# A modal and its subject with nothing after: "can you", "could we".
_MODALS: Final = _set("can could would will should shall may might do does did")
_SUBJECTS: Final = _set("you i we it he she they")
_QUESTION_WORDS: Final = _set("where what who how when why which")
_WORD = re.compile(r"[a-z0-9]+(?:'[a-z]+)?")


def words_of(text: str) -> list[str]:
    """Lower-case words, apostrophes kept ("let's"), punctuation dropped."""
    return _WORD.findall(text.lower().replace("\u2019", "'"))


def trails_off(text: str) -> bool:
    """Speech-to-text's own sign of an unfinished sentence: it ends on a comma, a dash,
    a colon or an ellipsis."""
    return bool(re.search(r"(,|-|\u2014|\u2013|:|\.\.\.|\u2026)\s*$", text.strip()))


def is_complete(text: str) -> bool:
    """Whether `text` (a transcript, wake phrase already removed) can be a whole request."""
    said = words_of(text)
    if not said or trails_off(text):
        return False
    last = said[-1]
    if last in _CONJUNCTIONS or last in _DETERMINERS or last in _PREPOSITIONS or last in _HESITATIONS:
        return False
    before = said[-2] if len(said) >= 2 else ""
    if last in _QUESTION_WORDS or (last in _OPEN_VERBS and before not in _DETERMINERS):  # "end the call" ends
        return False
    if before in _MODALS and last in _SUBJECTS:
        return False
    # "turn on" / "switch off" with nothing after: the particle is last but the object is missing
    # ("turn the projector off" is complete)
    return not (before in _OPEN_VERBS and last in {"on", "off", "up", "down"})
