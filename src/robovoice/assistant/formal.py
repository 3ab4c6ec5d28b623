"""Formal requests, as retired civil servants, teachers and officers in India write and say them,
put as a plain request for the reading only: "I am requesting you to …", "you may proceed to …",
a request in the passive ("The call may be disconnected", "the projector may be put off"), "prior
to that" (before that), and "Let the projector remain on" (leave it as it is).

Text test v123: the first three were talk (no call, no drive before the projector, only the
dock of three steps), and "Let the projector remain on" switched it on. A passive with a
reason or a condition after it ("the call may be disconnected if the signal drops") says what
could happen, not what to do.
"""

from __future__ import annotations

import re

_ASKING = re.compile(r"\b(?:i am|i'm|i|we are|we) (?:humbly |kindly |hereby )?(?:requesting|request"
                     r"|would like to request|beg) (?:of )?you to (?:kindly |please )?"
                     r"|\byou are (?:kindly |hereby )?requested to (?:kindly |please )?", re.IGNORECASE)
_YOU_MAY = re.compile(r"\byou (?:may|can now|may now|may kindly) (?:kindly |please )?(?=(?:proceed|go|come|move|head"
                      r"|switch|turn|put|call|ring|connect|disconnect|return|end|start|stop)\b)", re.IGNORECASE)
_THEN_NOT = r"(?!\s+(?:if|when|whenever|because|due|in case|unless)\b)"
_MAY_BE = r"(?:also |too )?(?:may|should|can|must|could|is to|has to|needs to|will) (?:also )?(?:kindly |please )?be"
_CALL_ENDED = re.compile(r"\b(?:the|this|that|my|our) (?:video )?call " + _MAY_BE
                         + r" (?:disconnected|ended|cut|terminated|closed|finished|stopped)\b" + _THEN_NOT,
                         re.IGNORECASE)
_SWITCHED = re.compile(r"\b(?:the|this|that) (projector|screen) " + _MAY_BE
                       + r" (?:put|switched|turned|kept|made) (on|off)\b" + _THEN_NOT, re.IGNORECASE)
_PRIOR = re.compile(r"\bprior to (?:that|this|it|the same)\b", re.IGNORECASE)
_REMAIN = re.compile(r"\blet (?:the (?:projector|screen)|it) (?:remain|stay|be|continue) (on|off)\b", re.IGNORECASE)


def as_asked(text: str) -> str:
    """`text` with its formal requests said plainly; unchanged where it has none."""
    text = _ASKING.sub("please ", _PRIOR.sub("before that", text))
    text = _YOU_MAY.sub("", text)
    text = _CALL_ENDED.sub("end the call", text)
    text = _SWITCHED.sub(lambda m: f"switch the {m.group(1).lower()} {m.group(2).lower()}", text)
    return _REMAIN.sub(lambda m: f"leave it {m.group(1).lower()}", text)
