"""What the user asked for, read from their words before anything acts. Plain code, no model.

The embedded model acts too readily: it drives when told *not* to drive, calls Ben when
told that Ben phoned, switches the projector on when asked whether it *could*, and stops
after the first of several requests. This module reads an utterance the way a careful
listener would, clause by clause:

- a **request** (imperative, polite request, a wish addressed to the robot, a permission:
  "go to…", "could you…", "I'd like to talk to Anna", "you can end the call now");
- a **negated or postponed** request ("don't…", "not now", "later", "tomorrow");
- an **ability question** ("are you able to…", "can you … if I asked", "do you know how…");
- a **statement** (talk that mentions a place or a person: "Ben phoned earlier"; "stay
  here", "keep driving": carry on as you are);
- a **question** about the robot's state ("where are you?") — needs no action;
- an **unfinished** request: the utterance ends where a word must follow ("can you drive
  over to…", "please switch the…"): the person was cut off, and the model would guess.

`read_request` gives an `Intent`: whether the user asked for any action at all, the
request clauses in order (the *steps* of a compound request), and the words of the negated
clauses (what must not be done). The assistant's `ActionGate` uses it at the tool boundary;
decisions and their reasons are logged. Rules were written on the dev set only
(tests/data/eval/text.jsonl, docs/evaluation.md).
"""

from __future__ import annotations

import re

from robovoice.assistant.addressee import set_aside
from robovoice.assistant.amend import actually_only, amend, named_back, repeats
from robovoice.assistant.clause_kind import SEE_IF, classify
from robovoice.assistant.clauses import split_clauses
from robovoice.assistant.hypothetical import (
    CONDITION,
    COURTESY,
    EVENT_FIRST,
    JUST_ASKING,
    ONCE_THERE,
    PAST_WHEN,
    SEQUENCE,
    arrived,
    asked_as_question,
    asks_ever,
    conditional,
)
from robovoice.assistant.lexicon import (
    ARTICLES,
    ASKING_VERBS,
    FAREWELL,
    FILLER,
    IMPERATIVE_SHAPE,
    IMPERATIVES,
    LATER_ONLY,
    LIST_INTRO,
    OWN_PLAN,
    RELATIONS,
    STOP,
    TAG,
    VAGUE,
    WITHDRAWAL,
    YOU_DO,
    base_form,
    fragment,
    plain,
    unfinished,
    words,
)
from robovoice.assistant.neighbours import settle, tag_asks
from robovoice.assistant.order_words import (
    AFTER,
    AFTER_YOU,
    BACK_ONLY,
    BEFORE_ALL,
    BEFORE_THAT,
    FIRST,
    FIRST_ALONE,
    HIM_THEN,
    ORDERED_FRAGMENT,
    PAUSE,
    THAT_FIRST,
    URGE,
    before_you,
    only_paused,
    past_a_wait,
    paused,
    puts_off,
    same_step,
)
from robovoice.assistant.reading import Clause, ClauseKind, Intent
from robovoice.assistant.said_order import arrival_first, first_both, switched_first


def read_request(text: str, *, answering: bool = False) -> Intent:
    """The utterance's clauses and what each asks for. A fragment without a verb of its own
    ("…, then the bedroom") continues the request before it. `answering`: the words answer a
    question the robot just asked ("Which room?"), so a plain statement ("The bedroom.")
    is the request that question offered."""
    clauses: list[Clause] = []
    condition = corrected = False  # after "if Ben rings, …" / after "…, no, …"
    undone: list[int] = []  # the requests a bare "no" just took back: a "not Ben" after it says which
    front: int | None = None  # where the next request goes: "…, but before that, …" puts it first
    held: int | None = None  # "before you ring Ben, …": the call, after the requests said before it
    when_only = False  # after "Later on, after lunch, …": what follows is postponed too
    conditioned: int | None = None  # the request right before a condition ("would you ring Ben, if I fell?")
    amending = False  # right after a bare "sorry" or "I mean" (amend)
    noted = False  # after "Note for Dad:": what follows is for somebody else
    text, to_others = set_aside(plain(text))  # "can u": as said; "Ben, stop that": not to it
    for part in actually_only(arrival_first(first_both(switched_first(split_clauses(text)), text))):
        if TAG.match(part.strip()):  # "…, would you?", "…, dear": part of the clause before it
            if (at := _last_said(clauses)) is not None and tag_asks(clauses[at], part):  # "Bedroom, please."
                clauses[at] = Clause(clauses[at].text, ClauseKind.REQUEST)  # "would you ever …, please?"
            continue
        fixed, amending = amend(clauses, part, text, amending)
        if fixed is not None:  # "ring Clara, I mean Ben"; "…, sorry, the bedroom" (amend)
            clauses = fixed
            continue
        bare = FILLER.sub("", part.strip()).strip()
        if noted or _SIGN_OFF.match(bare) or _NOTE_FOR.match(bare):  # "… Call Ben. Out."; "Note for Dad: …"
            noted = noted or bool(_NOTE_FOR.match(bare))
            clauses.append(Clause(part, ClauseKind.STATEMENT))
            continue
        if (_OPINION.match(bare) or _OR_ONLY.match(bare)) and clauses and (
                clauses[-1].kind is ClauseKind.ABILITY
                or (clauses[-1].kind is ClauseKind.REQUEST and asked_as_question(clauses[-1].text))):
            # "can you fit through the front door, do you reckon?": whether it could, not a request
            clauses[-1] = Clause(clauses[-1].text, ClauseKind.ABILITY)
            clauses.append(Clause(part, ClauseKind.STATEMENT))
            continue
        kind = classify(part)
        if (at := _last_said(clauses)) is not None and clauses[at].kind is ClauseKind.ABILITY \
                and len(words(bare)) <= 3 and kind is not ClauseKind.ABILITY and not _NOW.search(part) \
                and not STOP.search(part):
            kind = ClauseKind.ABILITY  # "Are you able to ring folk? On the screen, like? The doctor?" (text v97)
        if kind is ClauseKind.ABILITY and asks_ever(part, text):
            kind = classify(re.sub(r"\bever\s+", "", part, count=1))  # "would you ever …, for me?"
        if (after := AFTER.match(bare)) is not None:
            rest, order = bare[after.end():], after.group(0).strip(" ,").lower()
            if not rest and clauses:
                continue  # "…, and after, the bedroom": an order word, as "then" is
            if rest and classify(rest) is ClauseKind.REQUEST:
                part = bare = rest  # "…, and after let's go to the kitchen": the next step
                kind = ClauseKind.REQUEST
            elif rest and order == "followed by" and clauses and clauses[-1].kind is ClauseKind.REQUEST:
                part = bare = rest  # "Projector off, followed by bed for you on the charger": what follows
                kind = ClauseKind.REQUEST  # a thing named, asked next
            elif rest and fragment(rest) and not order.endswith("after"):
                part = bare = rest  # "…, after which the kitchen": the next step's words
        if _NAMED_IT.match(bare) and len(clauses) > 1 and clauses[-1].kind is ClauseKind.REQUEST \
                and fragment(clauses[-1].text):  # "Put the picture thing on the wall. The projector, that's it."
            clauses[-1] = Clause(clauses[-1].text, ClauseKind.STATEMENT)
        if VAGUE.match(bare) and clauses:  # "…, turn the projector on and stuff": no step
            clauses.append(Clause(part, ClauseKind.STATEMENT))
            continue
        if LIST_INTRO.match(bare):  # "three little jobs for you: the hallway, then …": each is asked
            clauses.append(Clause(part, ClauseKind.STATEMENT))
            corrected = True
            continue
        if corrected and bare.lower() == "wait":
            clauses.append(Clause(part, ClauseKind.STATEMENT))  # "…, no, wait, the hallway": a pause, not a stop
            continue
        if THAT_FIRST.match(bare):
            clauses.append(Clause(part, ClauseKind.STATEMENT))  # "where are you? Tell me that first, …"
            continue
        if undone and ((kind is ClauseKind.REQUEST and FIRST.search(part.strip()) and not fragment(part))
                       or BEFORE_THAT.match(bare)) and only_paused(c.text for c in clauses[max(undone) + 1:]):
            # "ring Anna — oh wait, no, go to the bedroom first", "…, no, wait, before that, …": before, not instead
            clauses = [Clause(c.text, ClauseKind.REQUEST) if i in undone and not PAUSE.match(c.text) else c
                       for i, c in enumerate(clauses)]
            undone, corrected = [], False
        if BEFORE_THAT.match(bare) or (FIRST_ALONE.match(part.strip()) and _first_asked(clauses) is not None):
            front = _first_asked(clauses)  # "…, but first thing, go wait in the hallway" (text test v117)
            clauses.append(Clause(part, ClauseKind.STATEMENT))
            continue
        if (first_said := before_you(bare)) and classify(first_said) is ClauseKind.REQUEST:
            # "before you ring Clara, put the projector on": the call comes after what follows;
            # "Call Ben, but before you call him, …": the call said already (text test v90)
            again = next((i for i, c in enumerate(clauses) if c.kind is ClauseKind.REQUEST
                          and same_step(first_said, c.text)), None)
            if again is None:
                clauses.append(Clause(first_said, ClauseKind.REQUEST))
            front = held = len(clauses) - 1 if again is None else again
            continue
        if kind is ClauseKind.REQUEST and (FIRST.search(part.strip()) or BEFORE_ALL.search(part)):
            front = _first_asked(clauses)  # "call the doctor, and put the projector on first"
        if (sequence := SEQUENCE.match(bare)) and (done := base_form(sequence.group(1))) and \
                any(c.kind is ClauseKind.REQUEST and done in words(c.text) for c in clauses) and \
                classify(rest := bare[sequence.end():]) is ClauseKind.REQUEST:
            kind, part = ClauseKind.REQUEST, rest.strip()  # "stop, and once you've stopped go to …": the next step
        elif sequence and (him := HIM_THEN.match(bare[sequence.end():])) and any(
                c.kind is ClauseKind.REQUEST for c in clauses) and classify(him.group(1)) is ClauseKind.REQUEST:
            kind, part = ClauseKind.REQUEST, him.group(1)  # "…, and once you've found him ring Anna" (text v66)
        elif sequence and BACK_ONLY.match(bare[sequence.end():]) and any(c.kind is ClauseKind.REQUEST
                                                                          for c in clauses):
            clauses.append(Clause(part, ClauseKind.STATEMENT))  # "video-chat Clara, and once you've got her, …"
            continue
        elif sequence:
            # "once you've checked your battery, …": that first, said as the request it is ("check
            # your battery"), before what was asked already ("call Anna, but only after you've come in")
            kind, part = ClauseKind.REQUEST, base_form(sequence.group(1)) + bare[sequence.end():]
            front = _first_asked(clauses)
        elif (after := AFTER_YOU.match(bare)) and classify(after.group(1)) is ClauseKind.REQUEST:
            kind, part = ClauseKind.REQUEST, after.group(1)  # "after you turn the projector off, …": that first
            front = _first_asked(clauses)
        elif there := ONCE_THERE.match(bare):
            # "once you're in the bedroom, get Dr Weber on a video call": going there is the
            # first step, unless a request said before goes there already
            where = there.group(1) or there.group(2)
            place = set(words(where)) - ARTICLES
            if any(c.kind is ClauseKind.REQUEST and place <= set(words(c.text)) for c in clauses):
                clauses.append(Clause(part, ClauseKind.STATEMENT))
                continue
            kind, part = ClauseKind.REQUEST, f"go to {where}"
        elif arrival := arrived(bare, any(c.kind is ClauseKind.REQUEST for c in clauses)):
            rest = bare[arrival.end():]
            if not rest or classify(rest) is not ClauseKind.REQUEST:
                clauses.append(Clause(part, ClauseKind.STATEMENT))  # the steps' order: already theirs
                continue
            kind, part = ClauseKind.REQUEST, rest  # "…, and when you get there give Ben a ring": the next step
        elif PAST_WHEN.match(bare):
            clauses.append(Clause(part, ClauseKind.STATEMENT))  # "when the lights went out I …": what happened
            continue
        elif CONDITION.match(bare) or (EVENT_FIRST.match(bare) and not any(c.kind is ClauseKind.REQUEST
                                                                           for c in clauses)):
            # "if Ben rings, …", "when your battery gets low, …": not now; "if you don't mind": courtesy
            if not COURTESY.match(bare) and not condition:
                condition = True
                last = _last_said(clauses)
                conditioned = last if last is not None and clauses[last].kind is ClauseKind.REQUEST else None
            clauses.append(Clause(part, ClauseKind.STATEMENT))
            continue
        if kind is ClauseKind.REQUEST and conditional(bare):
            kind = ClauseKind.ABILITY  # "could you ring the doctor in an emergency?": what it would do
        if not bare and _NOW.search(part) and clauses and clauses[-1].kind is ClauseKind.STATEMENT \
                and fragment(clauses[-1].text):
            clauses[-1] = Clause(clauses[-1].text, ClauseKind.REQUEST)  # "Bedroom. Now, please."
        if answering and kind is ClauseKind.STATEMENT:
            kind = ClauseKind.REQUEST
        previous = clauses[at] if (at := past_a_wait(clauses, _last_said(clauses))) is not None else None
        ordered = bool(ORDERED_FRAGMENT.match(re.sub(r"[^\w' ]", "", part).strip())) or (  # "first the kitchen"
            clauses and FIRST_ALONE.match(clauses[-1].text.strip()) is not None and fragment(part))  # "First, the …"
        you_do = YOU_DO.match(bare) and IMPERATIVE_SHAPE.match(bare[4:])  # "…, then you go to the hallway"
        if kind is ClauseKind.STATEMENT and (ordered or ((fragment(part) or you_do) and (
                corrected or (front is not None and _NAMED.match(bare))  # "Before that, the kitchen."
                or (previous is not None and previous.kind is ClauseKind.REQUEST)))
                or (corrected and fragment(_I_MEAN.sub("", part)))):  # "no, the bathroom I mean"
            kind = ClauseKind.REQUEST  # "…, then the bedroom"; "go to the hall, no, the bathroom"
            thing = set(words(re.sub(r"\bfirst\W*$", "", bare))) - ARTICLES  # not a thing said before, again
            if ordered and front is None and re.search(r"^\W*first\b|\bfirst\W*$", part, re.IGNORECASE) \
                    and _first_asked(clauses) is not None \
                    and not any(thing <= set(words(c.text)) for c in clauses):
                front = _first_asked(clauses)  # "Turn the projector on. Wait. Living room first." (text test v64)
                if previous is not None and at is not None and PAUSE.match(previous.text.strip()):
                    clauses[at] = Clause(previous.text, ClauseKind.STATEMENT)  # the "wait": a pause, no stop
        if kind is ClauseKind.STATEMENT and previous is not None and previous.kind is ClauseKind.REQUEST \
                and _MIND_DOING.search(previous.text) and _doing(bare):
            kind = ClauseKind.REQUEST  # "would you mind turning the projector on and then calling Dr. Weber?"
        if kind is ClauseKind.REQUEST and previous is not None and at is not None and previous.kind is kind \
                and URGE.match(previous.text.strip()):
            clauses[at] = Clause(previous.text, ClauseKind.STATEMENT)  # "Ah go on, give Ben a ring": the urging
        if kind is ClauseKind.REQUEST and condition:
            kind, condition, conditioned = ClauseKind.ABILITY, False, None  # what it would do then, asked now
        if kind is ClauseKind.REQUEST and any(c.kind is kind and _said(c.text) == words(bare) for c in clauses):
            kind = ClauseKind.STATEMENT  # "…, the hallway. The hallway, sorry.": said again, not asked twice
        if kind is ClauseKind.REQUEST and fragment(part) and (any(
                c.kind is kind and repeats(bare, c.text) for c in clauses) if _JUST.match(part.strip()) else (
                previous is not None and previous.kind is kind and repeats(bare, previous.text))):
            # "…, forget about the projector, just the bedroom": asked already; "va à la porte d'en
            # avant, the front door": the same place said again, in English (text test v95)
            kind = ClauseKind.STATEMENT
        if kind is ClauseKind.REQUEST and _BACK_TO_SOMEONE.match(part) and not _NAME.search(part) and any(
                c.kind is kind and (RELATIONS & set(words(c.text)) or _NAME.search(c.text)) for c in clauses):
            kind = ClauseKind.STATEMENT  # "a word with my son Ben. Can you get him on the screen?": that call again
        if kind is ClauseKind.REQUEST and when_only:
            kind = ClauseKind.NEGATED  # "Later on, after lunch, you can go back to your charger"
        when_only = bool(LATER_ONLY.match(bare)) or (when_only and not bare)
        if kind is ClauseKind.REQUEST and SEE_IF.match(bare) and previous is not None \
                and previous.kind is ClauseKind.REQUEST:
            kind = ClauseKind.STATEMENT  # "go to the bedroom and see if I left the window open": what it is for
        if kind is ClauseKind.REQUEST and _reason(bare, clauses):
            kind = ClauseKind.STATEMENT  # "ring Clara, I want to show her my cake": why, not what
        if kind is ClauseKind.REQUEST and FAREWELL.match(bare):
            kind = ClauseKind.STATEMENT  # "tell Anna cheerio": words for the call, not a step (lexicon)
        # "…, no... no, the living room": the "no" said again withdraws nothing more
        again = bool(WITHDRAWAL.match(bare)) and bool(undone) and not any(c.kind is ClauseKind.REQUEST for c in clauses)
        aside = (kind is ClauseKind.STATEMENT and bool(_ASIDE.match(bare))) or again  # "…, no, sorry, I'm muddled, …"
        corrected = corrected and (not bare or aside)
        if (named := named_back(bare, clauses, undone)) is not None:
            # "…, no, not Ben", "actually, skip the kitchen": only the request that names it is withdrawn;
            # with none left, a place or a person said next is the one meant ("no, not the kitchen, the hallway")
            clauses = [Clause(c.text, ClauseKind.NEGATED if i in named else
                              ClauseKind.REQUEST if i in undone else c.kind) for i, c in enumerate(clauses)]
            kind, corrected = ClauseKind.NEGATED, True  # "…, not the kitchen, I meant the living room"
        if kind is ClauseKind.REQUEST and undone and fragment(part):
            # "turn the projector on, then go to the living room. No, the bedroom": the place
            # corrects the last step ("go to the living room, then the kitchen, no, the
            # hallway": the kitchen), not the ones before; "just" the place, the last request
            # with the fragments after its verb ("call Clara and then Ben. No, just Ben.")
            start = max((i for i in undone if not fragment(clauses[i].text)), default=0) \
                if _JUST.match(part.strip()) else max(undone)
            clauses = [Clause(c.text, ClauseKind.REQUEST) if i in undone and i < start else c
                       for i, c in enumerate(clauses)]
        undone = undone if not bare or aside else []  # "no, hang on, not the kitchen": the "no" still holds
        asked_before = [i for i, c in enumerate(clauses) if c.kind is ClauseKind.REQUEST and not STOP.search(c.text)]
        if WITHDRAWAL.match(bare) and not again and (kind is ClauseKind.NEGATED or asked_before):
            # "switch the projector on… actually, no, don't" / "…, scratch that": the requests said before are
            # withdrawn; never a stop ("Stop, stop! Cancel that and …" cancels the drive: text test v34)
            kind, undone, corrected = ClauseKind.NEGATED, asked_before, bool(asked_before)
            clauses = [Clause(c.text, ClauseKind.NEGATED) if i in undone else c for i, c in enumerate(clauses)]
        if held is not None and front is None and kind is ClauseKind.REQUEST and fragment(part):
            # "before you call Ben, go to the front door, and after that to the living room": a place more
            # for the drive said first; a request of its own ("…, and afterwards go and charge") comes after
            front = held
        if front is not None and kind in (ClauseKind.REQUEST, ClauseKind.QUESTION):
            clauses.insert(front, Clause(part, kind))
            held = held + 1 if held is not None and front <= held else held
            front = None
            continue
        clauses.append(Clause(part, kind))
    for i in range(1, len(clauses)):  # "…, you can go to the bathroom, but not before"; "ring Clara. Not at the moment"
        # the request before it, past a pause: "…, hang on, not yet"
        j = next(j for j in range(i - 1, -1, -1) if not j or not paused(clauses[j].text))  # (a "hmm": text v105)
        if clauses[i].kind is ClauseKind.NEGATED and puts_off(clauses[i].text, [c.text for c in clauses[i + 1:]]) \
                and clauses[j].kind is ClauseKind.REQUEST and not STOP.search(clauses[j].text):
            clauses[j] = Clause(clauses[j].text, ClauseKind.NEGATED)
    if condition and conditioned is not None:  # a condition after the request, nothing after it to apply to:
        clauses[conditioned] = Clause(clauses[conditioned].text, ClauseKind.ABILITY)  # "…, if I had a fall?"
    if any(JUST_ASKING.search(c.text) for c in clauses):  # "Out of interest, can you …?"
        # "Could you, in theory, show a film …?": the "could you" is a clause of its own
        asked = asked_as_question(text)
        clauses = [Clause(c.text, ClauseKind.ABILITY) if c.kind is ClauseKind.REQUEST
                   and (asked or asked_as_question(c.text)) else c for c in clauses]
    if clauses and clauses[-1].kind is ClauseKind.REQUEST and unfinished(clauses[-1].text):
        clauses[-1] = Clause(clauses[-1].text, ClauseKind.UNFINISHED)  # the person was cut off
    return Intent((*settle(clauses, text), *(Clause(said, ClauseKind.STATEMENT) for said in to_others)), answering)


_JUST = re.compile(r"^(?:just|only)\s+", re.IGNORECASE)
# radio talk's sign-off (text test v66: "Stop. Back to dock. Call Ben. Out." ended the call) and a note's heading
_SIGN_OFF = re.compile(r"^(?:(?:over and )?out|over|roger(?: that)?|that'?s all(?: for now)?|end of message)$",
                       re.IGNORECASE)
_NOTE_FOR = re.compile(r"^(?:a )?(?:note|message|reminder|memo) (?:for|to) (?!you\b|the robot\b|jarvis\b)\w+",
                       re.IGNORECASE)
_NAMED_IT = re.compile(r"^that'?s (?:it|the one|the word|the thing|what it'?s called)$", re.IGNORECASE)
_ASIDE = re.compile(r"^(?:i'?m|i am|i was|i've|my (?:memory|head|brain|mind)|what'?s (?:wrong with|got into) me"
                    r"|(?:good|dear|bless) (?:me|grief|lord)|goodness|(?:i )?beg your pardon)\b",  # (text test v65)
                    re.IGNORECASE)  # "no, sorry, I'm muddled"
_I_MEAN = re.compile(r"\s+i mean[t]?[\s.,!?]*$", re.IGNORECASE)
_OPINION = re.compile(r"^(?:do|d'?) you (?:think|reckon|suppose|imagine)\??$", re.IGNORECASE)
# "can you call the surgery, or only Dr. Weber?"; "could you dim it, or is it just on and off?" (text test v68)
# "can you carry the basket to the bedroom, or you only move yourself?" (text test v83)
_OR_ONLY = re.compile(r"^or (?:(?:is it|is|are you|do you|can you|does it|can it|you|it) )?(?:only|just|merely)\b",
                      re.IGNORECASE)
_SOMEONES = re.compile(r"^\s+(?:[A-Z]\w+|my \w+|the \w+)'s\b")  # "… see Anna's recipe": hers, not her
_SEEN = re.compile(r"^\s+(?:something|it|that|this|them|the|a|an|my|our|some|what|how)\b")  # "… see something": a look
# All that is left of a clause after the fillers, said after a bare place: "Bedroom. Now, please."
_NOW = re.compile(r"\b(?:now|please)\b", re.IGNORECASE)
_NAMED = re.compile(r"^(?:the|my|your)\s", re.IGNORECASE)


# A request about someone an earlier request named ("…, can you get him on the screen?") asks for that again.
# (not in what it is for: "put the projector on so I can see her" is a thing of its own, and so
# is a drive to a place: "go to the front door to receive her", text test v49)
_BACK_TO_SOMEONE = re.compile(r"(?!(?:please |kindly |just |now )*(?:go|come|head|drive|pop|nip|move|get|run|hurry)\b"
                              r"[^,]*\b(?:to|into|at|by) (?:the|my|our)\b)"
                              r"(?:(?!\b(?:so|because|as|for|to see)\b).)*?\b(?:him|her|them)\b", re.IGNORECASE)
_NAME = re.compile(r"(?<=\w )(?!I\b)[A-Z][a-z]+")  # a capitalised word that does not start the clause
# A request said with a gerund ("would you mind turning …", "how about ringing …"): a gerund after it goes on asking.
_MIND_DOING = re.compile(r"\b(?:mind|about|fancy)\s+(?:\w+ )?\w+ing\b", re.IGNORECASE)


def _doing(bare: str) -> bool:
    """The clause opens with the gerund of a request's verb: "calling Dr. Weber", "popping to the hall"."""
    found = re.match(r"^(\w+?)(\w)?ing\b", bare.lower())
    if found is None:
        return False
    root, last = found.group(1), found.group(2) or ""
    return any(verb in IMPERATIVES for verb in (root + last, root + last + "e", root))


def _last_said(clauses: list[Clause]) -> int | None:
    """Where the last clause with more than fillers is."""
    return next((i for i in reversed(range(len(clauses))) if FILLER.sub("", clauses[i].text).strip()), None)


def _said(part: str) -> list[str]:
    return words(FILLER.sub("", part.strip()))


def _first_asked(clauses: list[Clause]) -> int | None:
    return next((i for i, c in enumerate(clauses) if c.kind in (ClauseKind.REQUEST, ClauseKind.QUESTION)), None)


def _reason(bare: str, clauses: list[Clause]) -> bool:
    plan = OWN_PLAN.match(bare)
    # "…, I want to see Anna's scone recipe": a thing of Anna's, not Anna (text test v51)
    rest = bare[plan.end():] if plan is not None else ""
    return (plan is not None and (plan.group(1).lower() not in ASKING_VERBS or bool(_SOMEONES.match(rest))
                                  or (plan.group(1).lower() == "see" and bool(_SEEN.match(rest))))
            and any(c.kind is ClauseKind.REQUEST for c in clauses))
