"""An utterance as `intent.read_request` reads it: its clauses, the kind of each, and what
the `Intent` they make asks for (the steps, what was declined, what a word points back at)."""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum

from robovoice.assistant.addressee import a_person
from robovoice.assistant.dialects import HOME_ROOM
from robovoice.assistant.lexicon import FILLER, IMPERATIVES, fragment, words


class ClauseKind(Enum):
    REQUEST = "request"
    NEGATED = "negated"  # also postponed: "later", "not now"
    ABILITY = "ability"
    STATEMENT = "statement"
    QUESTION = "question"
    UNFINISHED = "unfinished"  # a request cut off before its object: "can you drive over to…"


@dataclass(frozen=True, slots=True)
class Clause:
    text: str
    kind: ClauseKind


@dataclass(frozen=True, slots=True)
class Intent:
    """An utterance read clause by clause."""

    clauses: tuple[Clause, ...]
    answering: bool = False  # the words answer the robot's own question

    @property
    def asks_action(self) -> bool:
        """Some clause asks the robot to do something now."""
        return any(c.kind is ClauseKind.REQUEST for c in self.clauses)

    @property
    def _asked(self) -> tuple[Clause, ...]:
        return tuple(c for c in self.clauses if c.kind in (ClauseKind.REQUEST, ClauseKind.QUESTION))

    @property
    def steps(self) -> tuple[str, ...]:
        """The things asked, in the order they were said: the requests, and the questions
        asked beside them ("tell me where you are and how charged you are")."""
        return tuple(c.text for c in self._asked)

    @property
    def worded_steps(self) -> tuple[str, ...]:
        """`steps` as the model is told them one at a time: a place or a person said as a
        correction ("…, and then ring Ben, no, Anna") in the request it puts right ("ring
        Anna"). Alone, "Now do the next thing I asked: Anna." got "I don't know who Anna is."
        (text test v32). And "here" where the person said where they are ("I'm in the
        bathroom. Would you come over here to me?"): "come to the bathroom"; told "come over
        here to me" alone after a refused call, the model said it could not."""
        worded: list[str] = []
        for i, c in enumerate(self.clauses):
            if c.kind not in (ClauseKind.REQUEST, ClauseKind.QUESTION):
                continue
            before = [b for b in self.clauses[:i] if not _TAKING_BACK.match(FILLER.sub("", b.text.strip()))]
            righted = before[-1] if before and before[-1].kind is ClauseKind.NEGATED else None
            value = FILLER.sub("", c.text.strip()).strip()
            if righted is not None and fragment(c.text) and words(value)[0] not in IMPERATIVES \
                    and not _SAID_NOT.match(righted.text.strip()):
                worded.append(_put_right(righted.text, value))
            elif _HERE.search(c.text) and (where := _where_they_are(self.clauses[:i])) is not None:
                worded.append(f"come to {where}")
            elif (go := _GO_BARE.match(value)) and _LOOK_ONLY.match(value[go.end():]) and i \
                    and self.clauses[i - 1].kind is ClauseKind.STATEMENT \
                    and _PLACE_ALONE.match(said := FILLER.sub("", self.clauses[i - 1].text.strip()).strip()) \
                    and not a_person(said.split()[-1]) and said.lower() not in _NO_PLACE:
                rest = re.sub(r"^then\b\W*", "", value[go.end():].strip(), flags=re.IGNORECASE)
                # "The hallway. You go and look"
                worded.append(f"go to {said[0].lower()}{said[1:]}" + (f" and {rest}" if rest else ""))
            elif back := _BACK_TO_ROOM.match(value):
                worded.append(f"go to {back.group(1)}")  # "come back to the living room" went to the dock (v121)
            elif room := _ROOM_STEP.match(c.text.strip()):  # "First bathroom": a drive to "first bathroom" (v122)
                worded.append(f"go to the {room.group(1).lower()}")
            elif _DOCK_STEP.match(value):
                worded.append("go back to your charging dock")
            elif _LAST_FIRST.search(value) and fragment(_LAST_FIRST.sub("", value)):
                worded.append(_LAST_FIRST.sub("", value))  # "Living room first": the order is the hint's
            else:
                worded.append(c.text)
        return tuple(worded)

    @property
    def lookups(self) -> tuple[bool, ...]:
        """For each of `steps`: whether it only asks to be told something ("where are you",
        "tell me your battery level"), which a look-up answers and no action may."""
        return tuple(c.kind is ClauseKind.QUESTION or bool(_TELL_ME.match(FILLER.sub("", c.text.strip())))
                     for c in self._asked)

    @property
    def refusal(self) -> ClauseKind | None:
        """Why no action was asked for (the first non-request kind that explains it), or None."""
        if self.asks_action:
            return None
        for kind in (ClauseKind.NEGATED, ClauseKind.UNFINISHED, ClauseKind.ABILITY, ClauseKind.STATEMENT):
            if any(c.kind is kind for c in self.clauses):
                return kind
        return ClauseKind.QUESTION if self.clauses else None

    @property
    def carries_on(self) -> bool:
        """The words say to carry on as things are ("keep going", "don't stop") and ask nothing
        new: a stop or cancel is the one thing not asked for."""
        return not self.asks_action and any(
            (c.kind is ClauseKind.NEGATED and _STOPPING.search(c.text))
            or (c.kind is ClauseKind.STATEMENT and _CARRY_ON.match(FILLER.sub("", c.text.strip())))
            for c in self.clauses)

    @property
    def refers(self) -> bool:
        """A request points at something by a word that names nothing ("go there", "call her")."""
        return any(c.kind is ClauseKind.REQUEST and _REFERENCE.search(_STAY_THERE.sub("", c.text))
                   for c in self.clauses)

    def words(self) -> set[str]:
        return {w for c in self.clauses for w in words(c.text)}

    def negated_words(self) -> set[str]:
        """Words said only in negated clauses (what the user asked *not* to do)."""
        negated = {w for c in self.clauses if c.kind is ClauseKind.NEGATED for w in words(c.text)}
        asked = {w for c in self.clauses if c.kind is ClauseKind.REQUEST for w in words(c.text)}
        return negated - asked


_TELL_ME = re.compile(
    r"(?:(?:can|could|would|will) you (?:please )?|please )?(?:(?:(?:tell|let)\s+me|(?:try )?find out)\b"
    r"(?!\s+(?:go|drive|come|call|talk|speak))"
    # a check of the robot's own charge: "check how much battery you've got first" (not "check the
    # kitchen", a look in a place, which is a drive)
    r"|(?:check|see|look at)\b"
    r"(?= (?:how|what|your|the|if|whether)\b[^,;]*\b"
    r"(?:battery|batteries|charge|charged|charging|power level|juice)\b))", re.IGNORECASE)
_STOPPING = re.compile(r"\b(?:stop|stopping|halt|cancel|turn (?:back|round|around))\b", re.IGNORECASE)
_CARRY_ON = re.compile(r"(?:keep (?:going|driving|on|moving)|carry on|continue|go on)\b", re.IGNORECASE)
# "hold it right there", "stop there", "stay just there": where the robot is, no place to look up
# (text test v49: a drive to the kitchen refused as unclear, and the robot asked which room)
_STAY_THERE = re.compile(r"\b(?:stop|halt|hold it|stay|wait|freeze)(?: right| just)? there\b", re.IGNORECASE)
_REFERENCE = re.compile(r"\b(?:there|her|him|them|that one|this one|that place|that person|mine|hers|theirs)\b",
                        re.IGNORECASE)
# a going said without where, right after a place said alone: "The hallway. You go and you look if the
# post came." (text test v101: the step told to the model left the place out, and it looked with its camera)
_GO_BARE = re.compile(r"^(?:you\s+)?(?:go|come|head|pop|nip)\b"
                      r"(?!\s+(?:to|into|in|on|over|up|down|back|out|home|ahead)\b)"
                      r"\s*(?:and\s+)?(?:you\s+)?", re.IGNORECASE)
# … and what it is to do there, if anything: have a look ("check the oven is off" says what it is for)
_LOOK_ONLY = re.compile(r"^(?:(?:have |take )?(?:a )?(?:look|see|check)"
                        r"(?: around| round| (?:who|what|if|whether)\b.*)?)?"
                        r"(?:\s+then|\s+now)?\W*$",
                        re.IGNORECASE)
_NO_PLACE = frozenset({"ready", "steady", "set", "ok", "okay", "right", "well", "so", "now", "yes", "no", "then",
                       "anyway", "please", "quick", "come on", "go on", "off", "away"})
# a place said alone: one or two words, an article before them at most ("Hallway.", "the front door")
_PLACE_ALONE = re.compile(r"^(?:(?:the|my) )?[A-Za-z]+(?: (?:room|door|way|hall|dock))?$", re.IGNORECASE)
# "Living room first": the step as told to the model, the order said by the hint
# a room to come back to: the model heard "back" as the dock's (text test v121)
_BACK_TO_ROOM = re.compile(r"^(?:come|go|head|get) back (?:to|into) ((?:the |my |your )?" + HOME_ROOM + r")\b",
                           re.IGNORECASE)
# a room or the dock said alone as a step, as speech that searches for its words says it
# (after an order word only: a bare "Bedroom" step the model reads well)
_ROOM_STEP = re.compile(r"^(?:first|then|next|after that),? (?:the |my |your )?(" + HOME_ROOM + r")\W*$",
                        re.IGNORECASE)
_DOCK_STEP = re.compile(r"^(?:(?:first|then|next),? )?(?:home|(?:your )?plug|(?:your )?charging place)\W*$",
                        re.IGNORECASE)
_LAST_FIRST = re.compile(r",?\s+first\W*$", re.IGNORECASE)
# a bare "no" or "sorry" between a request and what puts it right; a request its own words
# declined ("don't go to the kitchen") is no request a place after it puts right
_TAKING_BACK = re.compile(r"^(?:no|nope|no wait|wait|sorry|(?:i )?beg your pardon|pardon(?: me)?|correction|or rather"
                          r"|rather|i mean[t]?)?[\s,.!]*$",
                          re.IGNORECASE)
_SAID_NOT = re.compile(r"^(?:don'?t|do not|never|not|no need)\b", re.IGNORECASE)
_COURTESY = re.compile(r"^(?:(?:could|can|would|will) you|please|just|now)\b[\s,]*", re.IGNORECASE)


# "come (over) here", "come to me", "join us": to where the person is
_HERE = re.compile(r"\b(?:come|get|pop|nip)\b(?!.*\b(?:to|into|in) (?:the|my|our|your)\b).*"
                   r"\b(?:here|to me|to us|join (?:me|us))\b", re.IGNORECASE)
# where the person said they are: "I'm in the bathroom", "we're sitting in the kitchen having tea"
_I_AM_IN = re.compile(r"^(?:i'?m|i am|we'?re|we are)\b(?: \w+){0,2}? (?:in|at) ((?:the|my|our) \w+(?: room| door)?)\b",
                      re.IGNORECASE)


def _where_they_are(said: Sequence[Clause]) -> str | None:
    """The place the person last said they are in, before a request to come to them."""
    for clause in reversed(said):
        if clause.kind is ClauseKind.STATEMENT and (where := _I_AM_IN.match(FILLER.sub("", clause.text.strip()))):
            return where.group(1)
    return None


def _put_right(request: str, value: str) -> str:
    """`request` with its place or person replaced by `value`: "could you go to the hallway" and
    "the front door" make "go to the front door"; "ring Ben" and "Anna" make "ring Anna"."""
    plain = _COURTESY.sub("", request.strip()).strip()
    way = re.match(r"^(.*?\b(?:to|into|in|at|on|with)\s+)(?:the |my |your )?[\w' .]+$", plain, re.IGNORECASE)
    if way is not None:
        return way.group(1) + value
    verb = re.match(r"^(\w+)\s", plain)
    return f"{verb.group(1)} {value}" if verb is not None else value
