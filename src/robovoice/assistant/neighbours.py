"""What a clause says about the clause beside it, once each has been read (`intent.read_request`).

A request said as a habit ("… every morning", "three times a day") is no request for now, and two
readings only a neighbour can give:

- **a time at the end of "there and back"** ("walk to the front door and back every morning",
  "go to the kitchen and back tomorrow") is the time of the whole trip: the request before the
  "back" is not for now either (text test v53: a doctor's advice drove the robot);
- **talk about the robot goes on** after "look at him go": a way said without a verb of its own
  ("Off to the bedroom like he owns the place", said while it drove) describes where it is going,
  it asks for nothing (text test v53).
"""

from __future__ import annotations

import re

from robovoice.assistant.amend import go_list
from robovoice.assistant.lexicon import FILLER, IMPERATIVES, LATER, words
from robovoice.assistant.reading import Clause, ClauseKind

# a habit: advice or a routine, not a request for now (a statement that names one stays talk)
_HABIT = re.compile(r"\b(?:every (?:single )?(?:morning|day|night|evening|afternoon|week|hour)|each (?:morning|day|"
                    r"night|evening)|(?:once|twice|\w+ times) a (?:day|week)|daily)\b", re.IGNORECASE)
_BACK = re.compile(r"^(?:and )?back\b", re.IGNORECASE)
# the robot watched and talked about in the third person
_WATCHED = re.compile(r"^(?:(?:just |oh )?(?:look|see|watch)(?: at)? (?:it|him|her|that thing|the robot|the wee thing)"
                      r"(?: go(?:es)?| go on| move| off)?)\W*$", re.IGNORECASE)


def settle(clauses: list[Clause], text: str) -> list[Clause]:
    """`clauses` of `text` as their neighbours read them: the bare places of a "then" list
    (`amend.go_list`), a habit, "… and back" with a time, a way said while the robot is watched."""
    out = [Clause(c.text, ClauseKind.NEGATED) if c.kind is ClauseKind.REQUEST and _HABIT.search(c.text) else c
           for c in go_list(clauses, text)]
    for i in range(1, len(out)):
        before, clause = out[i - 1], out[i]
        text = FILLER.sub("", clause.text.strip()).strip()
        if clause.kind is ClauseKind.NEGATED and before.kind is ClauseKind.REQUEST and _BACK.match(text) \
                and (LATER.search(text) or _HABIT.search(text)):
            out[i - 1] = Clause(before.text, ClauseKind.NEGATED)
        elif clause.kind is ClauseKind.REQUEST and _WATCHED.match(FILLER.sub("", before.text.strip()).strip()) \
                and _described(text):
            out[i] = Clause(clause.text, ClauseKind.STATEMENT)
    return out


def _described(text: str) -> bool:
    """No verb of a request of its own and no "you": where the robot goes, told, not asked."""
    said = words(text)
    return bool(said) and said[0] not in IMPERATIVES and "you" not in said and "please" not in said
