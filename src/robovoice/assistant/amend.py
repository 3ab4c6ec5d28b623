"""Readings of corrections and lists of steps that the clause-by-clause reading in `intent`
cannot make one clause at a time.

- **A correction that names what it takes back**: "…, no, not Ben", "actually, skip the
  kitchen" (`named_back`): just the requests that name it are taken back.
- **A correction said without "no"**: "ring Clara — sorry, I mean Ben — and …", "go to the
  kitchen, or rather the bedroom". A place, a person or a state said right after "sorry",
  "I mean", "or rather", "correction" or "make that" puts right the last request, as
  "…, no, Ben" does; without this it read as one more step ("ring Clara" and "Ben").
- **A list of places sent off with a bare "go"**: "Kitchen, then bedroom, then the dock. Off
  you go." The places alone read as talk (a bare "the kitchen" is no request); the "go" with
  no place of its own says they are its steps.
- **"actually, just …" after a request** (`actually_only`): only what follows is wanted, as
  after "no, just …".

Written on the dev set (tests/data/eval/text.jsonl: amend-*, golist-*).
"""

from __future__ import annotations

import re

from robovoice.assistant.clause_kind import classify
from robovoice.assistant.dialects import ROOM
from robovoice.assistant.lexicon import (
    ARTICLES,
    FILLER,
    IMPERATIVES,
    LIST_INTRO,
    NOT_NAMES,
    NOT_THAT,
    TAG,
    WITHDRAWAL,
    fragment,
    words,
)
from robovoice.assistant.reading import Clause, ClauseKind

_MARK = re.compile(r"^(?:sorry|(?:i )?beg your pardon|pardon(?: me)?|i mean[t]?|or rather|rather|correction"
                   r"|make (?:that|it)"
                   # a pause said before the value it puts right: "Go to the kitchen. Wait, the bathroom" (a
                   # bare "wait" only: "…, wait by the door" is a step)
                   r"|(?:(?:oh|ah) )?(?:wait|hang on|hold on)(?=\s*[,:;.\u2013\u2014-]|\s*$))\b[\s,:;.-]*",
                   re.IGNORECASE)
# what follows "I mean" and is no place or person: "…, I mean it", "…, sorry love"
_NOT_A_VALUE = re.compile(r"^(?:it|that|this|so|well|business|what i say|honestly|really|again|everyone|folks|all"
                          r"|about (?:that|this)|my (?:mistake|fault|bad|error)|wrong one)$", re.IGNORECASE)
_PAUSED = re.compile(r"^(?:(?:oh|ah) )?(?:wait|hang on|hold on)\b", re.IGNORECASE)
# "…, hang on, not yet"; "…. Hang on. Hallway first": a request taken back, a step put before it
_BEFORE_OR_NOT = re.compile(r"^(?:not|no|never)\b|\b(?:first|before)\b", re.IGNORECASE)
_MARK_AFTER = re.compile(r"[\s,]+(?:i mean[t]?|sorry)\W*$", re.IGNORECASE)
_ON_WORDS = r"\b(?:and|then|next|after|afterwards|also|too|plus|as well)\b"  # "…, then the bedroom": one more step
_GOES_ON = re.compile(_ON_WORDS, re.IGNORECASE)


def marker_rest(part: str, text: str) -> str | None:
    """What follows a correction word that starts `part` ("" for a bare "sorry"), or None; None
    too for a bare one that the utterance `text` goes on from ("…, sorry, and then …": the clause
    split drops that "and then")."""
    said = part.strip()
    mark = _MARK.match(said)
    if mark is None:
        return None
    if not said[mark.end():] and re.search(re.escape(said) + r"[\s,;:.\u2013\u2014-]*" + _ON_WORDS, text,
                                          re.IGNORECASE):
        return None
    if not said[mark.end():] and _PAUSED.match(said) and not re.search(re.escape(said) + r"\W*\w", text):
        return None  # "Go to the garage. Wait!": a "wait" said last is asked (a stop), no correction
    return said[mark.end():].strip()


def puts_right(said: str) -> bool:
    """Whether `said` (what follows a correction word, or all of the clause after a bare one)
    names the value that replaces the last request's: a place, a person, "on" or "off"."""
    value = FILLER.sub("", said).strip(" .,!?")
    return bool(value) and fragment(said) and not _GOES_ON.search(said) and not _NOT_A_VALUE.match(value) \
        and not _BEFORE_OR_NOT.search(value) \
        and not TAG.match(value) and not WITHDRAWAL.match(value)


def last_request(clauses: list[Clause]) -> int | None:
    """The index of the request said last, when nothing but a bare correction word came after
    it ("…, not the kitchen, I meant …" is put right already), or None."""
    for i in range(len(clauses) - 1, -1, -1):
        if clauses[i].kind is ClauseKind.REQUEST:
            return i
        if not _MARK.fullmatch(clauses[i].text.strip()):
            return None
    return None


def repeats(said: str, request: str) -> bool:
    """Whether `said` only says again what `request` names ("the hallway, I meant the hallway")."""
    return set(words(FILLER.sub("", said))) - ARTICLES <= set(words(request))


def amend(clauses: list[Clause], part: str, text: str, pending: bool) -> tuple[list[Clause] | None, bool]:
    """The clauses with `part` read as a correction (None: it is none), and whether the next
    clause may be one (after a bare "sorry"). `pending`: the clause before was a bare one."""
    if (wanted := instead(clauses, part)) is not None:
        return wanted, False
    last, rest = last_request(clauses), marker_rest(part, text)
    paused = bool(_PAUSED.match(part.strip())) or (pending and bool(clauses) and bool(_PAUSED.match(
        clauses[-1].text.strip())))
    if last is None:
        return None, False
    if rest == "":
        return [*clauses, Clause(part, ClauseKind.STATEMENT)], True
    said = rest if rest is not None else part if pending else None
    if said:  # "…. Oh wait, the bedroom I mean"
        said, part = _MARK_AFTER.sub("", said), _MARK_AFTER.sub("", part)
    if not said or not puts_right(said) or repeats(said, clauses[last].text):
        return None, False
    if paused and not _same_kind(said, clauses[last].text):
        return None, False  # after a bare "wait": only a place for a drive, a name for a call
    fixed = [Clause(c.text, ClauseKind.NEGATED) if i == last else c for i, c in enumerate(clauses)]
    state = re.fullmatch(r"\W*(on|off)\W*", FILLER.sub("", said), re.IGNORECASE)
    if state and re.search(r"\b(?:on|off)\b", clauses[last].text, re.IGNORECASE):
        # "turn the projector on, I mean off": a state names no thing; the request it puts right does
        part = re.sub(r"\b(?:on|off)\b", state[1].lower(), clauses[last].text, flags=re.IGNORECASE)
    return [*fixed, Clause(part, ClauseKind.REQUEST)], False


# "…, the bedroom instead", "…, just the bedroom"; after a bare "not the bathroom", "…, the bedroom"
_INSTEAD = re.compile(r"\b(?:just|only) (?:the|my|your|to) \w|\b(?:instead|rather)$", re.IGNORECASE)
_NOT_THERE = re.compile(r"\b(?i:not there)$")  # a place declined without its name ("nah, not there")
_NAMES_ONE = re.compile(r"\b(?:the|my|your) \w|(?<=\w )[A-Z][a-z]+|" + _NOT_THERE.pattern)


def instead(clauses: list[Clause], part: str) -> list[Clause] | None:
    """The clauses with `part` as the request it is when it names, without a verb, what is
    wanted in place of what was just declined ("Don't bother with the bathroom, just the
    bedroom.", "Not the kitchen, the hallway."), or None."""
    said = FILLER.sub("", part.strip()).strip(" .,!?")
    before = next((c for c in reversed(clauses) if FILLER.sub("", c.text.strip()).strip()), None)
    if before is None or before.kind is not ClauseKind.NEGATED or not said or not fragment(part) \
            or not (_NAMES_ONE.search(before.text) or _INSTEAD.search(part.strip(" .,!?"))) \
            or WITHDRAWAL.match(said) or TAG.match(said) \
            or any(c.kind is ClauseKind.REQUEST and repeats(said, c.text) for c in clauses):
        return None  # (not what was asked already: "go to the lounge, not the bedroom, mind, the lounge")
    after_not = re.match(r"^(?:no,? )?not\b", before.text.strip(), re.IGNORECASE) is not None
    not_there = _NOT_THERE.search(before.text.strip()) is not None  # "nah, not there. bathroom" (text test v45)
    if _INSTEAD.search(part.strip(" .,!?")) or (after_not and (
            not_there or re.match(r"^(?:the|my|your) \w", said, re.IGNORECASE))):
        return [*clauses, Clause(part, ClauseKind.REQUEST)]
    return None


# somebody who did something ("Ben phoned, then Clara. Off you go."): news, not a place
_DID = re.compile(r"^[A-Z]\w* (?:\w+ed|rang|rung|came|went|left|said|told|wrote|sent)$")
# a way to a place, said without a verb: "back to dock", "back on your dock", "on to the kitchen"
_TOWARDS = re.compile(r"^(?:back|on|over) (?:to|into|onto|on) (?:the |my |your )?\w+(?: \w+)?$", re.IGNORECASE)
_GREETING = re.compile(r"^(?:(?:good )?(?:morning|afternoon|evening|night)|hello|hi|hiya|thanks|thank you|cheers|"
                       r"sorry|bye|goodbye|ta)\W*$", re.IGNORECASE)
_GO_ALONE = re.compile(r"^(?:go|go now|let'?s go|away you go|on you go|get going|get moving|go go go)$",
                       re.IGNORECASE)


_AFTER_THAT = re.compile(r"\b(?:after that|afterwards)\b", re.IGNORECASE)


def _then_before(clause: Clause, text: str) -> bool:
    """`clause` is said right after a "then" or an "after that" (a comma or "and" between)."""
    return re.search(r"\b(?:then|after that|afterwards),?\s+" + re.escape(clause.text.strip()), text,
                     re.IGNORECASE) is not None


def go_list(clauses: list[Clause], text: str) -> list[Clause]:
    """`clauses` with the bare places of a "then" list made requests when a "go" without a
    place of its own sends the robot off ("Bathroom, then bedroom. Go."; the "go" is then no
    step of its own, nor after a list of requests: "Bathroom first, then your charger. Go
    now."), or when the list ends or starts with a bare place that reads as a request already
    ("Bathroom, then bedroom, then back to dock."). A heading before a colon ("Evening round:
    …") stays talk, and so do a name inside a sentence and news ("Ben phoned, then Clara")."""
    if "then" not in words(text) and not _AFTER_THAT.search(text):
        return clauses
    go = [i for i, c in enumerate(clauses)
          if c.kind is ClauseKind.REQUEST and _GO_ALONE.match(FILLER.sub("", c.text.strip()).strip(" .!"))]
    places = {i for i, c in enumerate(clauses) if c.kind is ClauseKind.STATEMENT and fragment(c.text)
              and words(c.text)[:1] != ["wait"]  # "…, no, wait, I mean Dr Weber, and then …": a pause (text v20)
              and not re.search(re.escape(c.text.strip()) + r"\s*:", text) and not _DID.match(c.text.strip())
              and not _a_name(c.text.strip(), text) and not LIST_INTRO.match(FILLER.sub("", c.text.strip()))}
    others = [i for i, c in enumerate(clauses) if c.kind is ClauseKind.REQUEST and i not in go]
    if go and (places or others):
        steps = places
    else:
        # "…, then back to dock"; "hallway, then bedroom, please" (a bare place asked with "please")
        go, steps = [], {i for i, c in enumerate(clauses) if (_TOWARDS.match(FILLER.sub("", c.text.strip()))
                         and (i in others or c.kind is ClauseKind.STATEMENT))
                         or (i in others and fragment(c.text) and words(c.text)[0] not in IMPERATIVES)}
        # "Bedroom. Then call Ben.": a bare place said first, right before "then" and a request, is a step too
        # (text test v52)
        # ("Bathroom, then the bedroom, and then home to the dock with you": the places before it too, text v63)
        said = [i for i, c in enumerate(clauses) if FILLER.sub("", c.text).strip()]
        first = said[0] if said else None
        run = first
        while run is not None and run + 1 in places and _then_before(clauses[run + 1], text):
            run += 1
        if first in places and run is not None and run + 1 in others \
                and words(clauses[first].text)[0] not in IMPERATIVES \
                and not _GREETING.match(clauses[first].text.strip()) and _then_before(clauses[run + 1], text):
            steps |= set(range(first, run + 1))
        # "front door, after that the kitchen": nothing but places, one after the other (text test v63)
        # (not a question: "kitchen, then the bedroom?", where the glasses may be)
        if len(said) > 1 and set(said) <= places and said == list(range(said[0], said[-1] + 1)) \
                and not text.rstrip().endswith("?") \
                and not any(_GREETING.match(clauses[i].text.strip()) for i in said) \
                and all(_then_before(clauses[i], text) for i in said[1:]):
            steps |= set(said)
        # … or said first and called out, talk after it: "Kitchen, then hallway, then the front door! It's a
        # treasure hunt!" (text test v109); not "Kitchen, then the bedroom, that's where I looked."
        lead = said[:1] if said and said[0] in places else []
        while lead and lead[-1] + 1 in places and _then_before(clauses[lead[-1] + 1], text):
            lead.append(lead[-1] + 1)
        if len(lead) > 1 and re.search(re.escape(clauses[lead[-1]].text.strip()) + r"\s*!", text) \
                and not any(_GREETING.match(clauses[i].text.strip()) for i in lead):
            steps |= set(lead)
            places = {i for i in places if i <= lead[-1]}  # what is called out after the "!" is talk: "Race you!"
        while grown := {i for i in places - steps if i - 1 in steps or i + 1 in steps}:
            steps |= grown
    return [Clause(c.text, ClauseKind.REQUEST) if i in steps else
            Clause(c.text, ClauseKind.STATEMENT) if i in go else c for i, c in enumerate(clauses)]


def named_back(bare: str, clauses: list[Clause], undone: list[int]) -> set[int] | None:
    """The requests said before that a "not Ben" or "skip the kitchen" names (None when it names
    none of them, or is no such clause): just those are taken back."""
    match = NOT_THAT.match(bare)
    if match is None:
        return None
    named = set(words(match.group(1))) - NOT_NAMES
    hit = {i for i, c in enumerate(clauses)
           if (c.kind is ClauseKind.REQUEST or i in undone) and named & set(words(c.text))}
    return hit or None


def _a_name(said: str, text: str) -> bool:
    """Whether `said` opens with a capital inside a sentence of `text` ("…, then Clara"): a
    person, not a place (a place is written small there: "…, then the kitchen")."""
    at = text.find(said)
    before = re.sub(r"(?:\b(?:and|then)\b|[\s,;\u2013\u2014-])*$", "", text[:max(at, 0)])
    return said[:1].isupper() and bool(before) and before[-1] not in ".!?:"


_ACTUALLY = re.compile(r"^\s*actually\b[\s,]*", re.IGNORECASE)
_ONLY_THIS = re.compile(r"^(?:just|only)\s+(?!(?:a|one) (?:sec|second|minute|moment|mo)\b)", re.IGNORECASE)


def actually_only(parts: list[str]) -> list[str]:
    """"…, actually, just end the call" after a request: only what follows is wanted, as after
    "no, just …" (text test v36: "Tell Anna I'm flagging... actually, just end the call")."""
    out: list[str] = []
    for i, part in enumerate(parts):
        said = _ACTUALLY.match(part)
        rest = part[said.end():] if said else ""
        after = rest or (parts[i + 1].strip() if i + 1 < len(parts) else "")
        if said and _ONLY_THIS.match(after) and any(classify(p) is ClauseKind.REQUEST for p in out):
            out += ["no", rest] if rest else ["no"]
        else:
            out.append(part)
    return out


def _same_kind(value: str, request: str) -> bool:
    """`value` names what `request` asks for: a room for a drive there, a name for a call."""
    if words(value)[:1] and words(value)[0] in IMPERATIVES:
        return False  # "…. Hang on, call Ben.": a request of its own
    if re.search(ROOM, value, re.IGNORECASE):
        return bool(re.search(ROOM + r"|\b(?:go|drive|head|come|move|pop|nip)\b", request, re.IGNORECASE))
    return bool(re.search(r"\b(?:call|ring|phone|video|facetime|dial)\b", request, re.IGNORECASE))


def room_put_right(clauses: list[Clause]) -> list[Clause]:
    """A room said alone, then a bare "no", then words with another room: the first is taken back
    ("bathroom, no, hallway. Go there.": audio test v113 drove to the bathroom; "The kitchen? No. Go
    to the hallway.")."""
    out = list(clauses)
    for i in range(len(out) - 2):
        first, no, then = out[i], out[i + 1], out[i + 2]
        if first.kind is ClauseKind.STATEMENT and _ROOM_ALONE.match(FILLER.sub("", first.text.strip()).strip()) \
                and _BARE_NO.match(no.text.strip()) \
                and (m := re.search(ROOM, then.text, re.IGNORECASE)) and m.group(0).lower() not in first.text.lower():
            out[i] = Clause(first.text, ClauseKind.NEGATED)
    return out


_ROOM_ALONE = re.compile(r"^(?:the |my |your )?" + ROOM + r"\W*$", re.IGNORECASE)
_BARE_NO = re.compile(r"^(?:no|nope|nah|not that)\W*$", re.IGNORECASE)
