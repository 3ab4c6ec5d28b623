"""What a clause says about the clause beside it, once each has been read (`intent.read_request`).

A request said as a habit ("… every morning", "three times a day") is no request for now, and two
readings only a neighbour can give:

- **a time at the end of "there and back"** ("walk to the front door and back every morning",
  "go to the kitchen and back tomorrow") is the time of the whole trip: the request before the
  "back" is not for now either (text test v53: a doctor's advice drove the robot);
- **talk about the robot goes on** after "look at him go" or "there he goes": a way said without a verb of its own
  ("Off to the bedroom like he owns the place", said while it drove) describes where it is going,
  it asks for nothing (text test v53).
"""

from __future__ import annotations

import re

from robovoice.assistant.addressee import a_person
from robovoice.assistant.amend import go_list, room_put_right
from robovoice.assistant.clause_kind import classify
from robovoice.assistant.dialects import ROOM
from robovoice.assistant.lexicon import (
    ARTICLES,
    ASKING_VERBS,
    FILLER,
    HASTE,
    IMPERATIVES,
    LATER,
    LIST_INTRO,
    OWN_PLAN,
    base_form,
    fragment,
    words,
)
from robovoice.assistant.order_words import BEFORE_THAT, PAUSE, paused
from robovoice.assistant.reading import Clause, ClauseKind

# a habit: advice or a routine, not a request for now (a statement that names one stays talk)
_HABIT = re.compile(r"\b(?:every (?:single )?(?:morning|day|night|evening|afternoon|week|hour)|each (?:morning|day|"
                    r"night|evening)|(?:once|twice|\w+ times) a (?:day|week)|daily)\b", re.IGNORECASE)
_BACK = re.compile(r"^(?:and )?back\b", re.IGNORECASE)
# the robot watched and talked about in the third person
_WATCHED = re.compile(r"^(?:(?:just |oh )?(?:look|see|watch)(?: at)? (?:it|him|her|that thing|the robot|the wee thing)"
                      r"(?: go(?:es)?| go on| move| off)?"
                      r"|(?:and )?(?:there|off|away) (?:he|she|it) goes(?: again)?)\W*$",
                      re.IGNORECASE)
# what the speaker will do next, said of themselves ("I'll pop the milk in the fridge"), no "you" in it
_OWN_NEXT = re.compile(r"^(?:(?:ok(?:ay)?|right|so|well),? )?i(?:'ll| will| shall|'m (?:going to|about to)|'ve got to"
                       r"| have to| must|'d better| better)\s+(?!.*\byou\b)(?!(?:need|want|like|ask|get)\b)\w+",
                       re.IGNORECASE)
_ASKED = re.compile(r"\b(?:for me|please|for us)\b", re.IGNORECASE)  # "I'll wait here and call Anna for me"
# a tag that says the clause before it is news ("…, just so you know", audio test v49: misheard, it drove)
_TOLD = re.compile(r"^(?:(?:just )?so (?:you know|you're aware)|for your information|fyi|(?:i'm )?just (?:saying|"
                   r"letting you know))\W*$", re.IGNORECASE)
_ROOM_ALONE = re.compile(r"(?:the |my )?" + ROOM, re.IGNORECASE)  # a room named and nothing else
_NOT_THAT = re.compile(r"^(?:(?:no|but|oh),? )*not (?:(?:the|my|your|to the) \w+(?: \w+)?|there|" + ROOM + ")$",
                       re.IGNORECASE)
# the first word of a way told, not asked ("off to the bedroom", "into the kitchen")
_WAYS = frozenset({"off", "into", "to", "back", "away", "out", "up", "down", "round", "over", "through", "towards",
                   "in", "across", "along"})


def settle(clauses: list[Clause], text: str) -> list[Clause]:
    """`clauses` of `text` as their neighbours read them: the bare places of a "then" list
    (`amend.go_list`), a habit, "… and back" with a time, a way said while the robot is watched."""
    out = [Clause(c.text, ClauseKind.NEGATED) if c.kind is ClauseKind.REQUEST and _HABIT.search(c.text) else c
           for c in go_list(clauses, text)]
    for i, clause in enumerate(out):  # "I wanna make sure, so call her": why, said first (text test v26)
        plan = OWN_PLAN.match(FILLER.sub("", clause.text.strip()).strip())
        if clause.kind is ClauseKind.REQUEST and plan and plan.group(1).lower() not in ASKING_VERBS \
                and any(c.kind is ClauseKind.REQUEST for c in out[i + 1:]):
            out[i] = Clause(clause.text, ClauseKind.STATEMENT)
    for i in range(1, len(out)):
        before, clause = out[i - 1], out[i]
        said = FILLER.sub("", clause.text.strip()).strip()
        if clause.kind is ClauseKind.NEGATED and before.kind is ClauseKind.REQUEST and _BACK.match(said) \
                and (LATER.search(said) or _HABIT.search(said)):
            out[i - 1] = Clause(before.text, ClauseKind.NEGATED)
        elif before.kind is ClauseKind.REQUEST and _TOLD.match(clause.text.strip()) \
                and _joined(before, clause, text, r"\s*[,\u2013\u2014-]+\s*"):
            out[i - 1] = Clause(before.text, ClauseKind.STATEMENT)  # "…, just so you know": news, not asked
        elif clause.kind is ClauseKind.REQUEST and _WATCHED.match(FILLER.sub("", before.text.strip()).strip()) \
                and _described(said):
            out[i] = Clause(clause.text, ClauseKind.STATEMENT)
    out = _name_list(_said_to(_after_its_name(_past_why(_left_as_is(_counted(_dont_again(out))), text)), text), text)
    out = _room_then(room_put_right(out), text)
    return _either_or(_before_that_last(_before_that_both(_done_too(_own_and(_not_that_but(out), text), text), text),
                                        text), text)


# "leave it on", "leave it alone": as it is (text test v107: "Turn off projector... leave it on" switched it off)
_LEAVE_IT = re.compile(r"^(?:(?:no|actually|oh|wait|sorry),? )*(?:just )?leave (?:it|that|them)"
                       r" (on|off|alone|be|as (?:it is|they are))\W*$", re.IGNORECASE)


# "Call Ben. Wait, don't call him yet.", "…, sorry, wait wait, don't call anybody first": the request
# said before with the same verb is taken back (text test v113 rang Ben, and stopped for the "wait")
_DONT_AGAIN = re.compile(r"^(?:(?:oh|no|sorry|actually|wait|hang on|hold on|eh|um|er),? )*(?:(?:please|just) )?"
                         r"(?:don'?t|do not) (\w+)(?: (?:him|her|them|it|that|anybody|anyone|anything|anywhere|there))?"
                         r"(?: (?:yet|now|just now|right now|first|after all|at all|then|today|please|up|on|off))*\W*$",
                         re.IGNORECASE)
_CALLING = frozenset({"call", "ring", "phone", "dial", "video", "facetime", "contact"})
_GOING = frozenset({"go", "drive", "head", "move", "come", "pop", "nip", "run"})
_ONE_VERB = (_CALLING, _GOING, frozenset({"switch", "turn", "put"}))  # verbs that ask for the same thing


def _room_then(clauses: list[Clause], text: str) -> list[Clause]:
    """"Living room. Projector on.": a room said alone as the first sentence, a request after it, is
    the first step (text test v115: the projector came on where the robot stood); not where that
    drive is asked anyway ("Bathroom. Go.", "Living room. Call Anna. Living room first, …")."""
    if len(clauses) > 1 and clauses[0].kind is ClauseKind.STATEMENT and clauses[1].kind is ClauseKind.REQUEST \
            and _ROOM_ALONE.fullmatch(clauses[0].text.strip()) \
            and _joined(clauses[0], clauses[1], text, r"\s*[.!]\s*") \
            and not set(words(clauses[1].text)[:1]) & _GOING \
            and not any(set(words(clauses[0].text)) - ARTICLES <= set(words(c.text)) for c in clauses[1:]):
        return [Clause(clauses[0].text, ClauseKind.REQUEST), *clauses[1:]]
    return clauses


def _dont_again(clauses: list[Clause]) -> list[Clause]:
    """A "don't" with the verb of a request said before it takes that request back (`_DONT_AGAIN`);
    a bare "wait" said between a request and more words is a pause, no stop ("Call Ben. Ah, wait,
    before that go to the hallway": text test v116 stopped the robot after the call)."""
    out = list(clauses)
    for i in range(1, len(out) - 1):
        if out[i].kind is ClauseKind.REQUEST and PAUSE.match(out[i].text.strip()) \
                and any(c.kind in (ClauseKind.REQUEST, ClauseKind.NEGATED) and not PAUSE.match(c.text.strip())
                        for c in out[:i]) \
                and any(FILLER.sub("", c.text.strip()).strip() for c in out[i + 1:]):
            out[i] = Clause(out[i].text, ClauseKind.STATEMENT)
    for i, clause in enumerate(out):
        again = _DONT_AGAIN.match(FILLER.sub("", clause.text.strip()).strip())
        if clause.kind is not ClauseKind.NEGATED or again is None:
            continue
        verb = base_form(again.group(1).lower())
        verbs = next((v for v in _ONE_VERB if verb in v), frozenset({verb}))
        for j in range(i):
            said = words(FILLER.sub("", out[j].text.strip()))
            if out[j].kind is ClauseKind.REQUEST and said and base_form(said[0]) in verbs:
                out[j] = Clause(out[j].text, ClauseKind.NEGATED)
    return out


_NUMBERS = frozenset({"one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "go"})


def _counted(clauses: list[Clause]) -> list[Clause]:
    """"…before I count to ten! One, two...": a count is no step (text test v109); a bare "go" said
    alone after it stays what it was (a "ready, steady, go" is read elsewhere)."""
    return [Clause(c.text, ClauseKind.STATEMENT) if c.kind is ClauseKind.REQUEST and (said := words(c.text))
            and set(said) <= _NUMBERS and set(said) != {"go"} else c for c in clauses]


def _left_as_is(clauses: list[Clause]) -> list[Clause]:
    """"Turn off the projector. Actually, leave it on.": the switch said just before is taken back; not
    "switch it on and leave it on" (the same way)."""
    out = list(clauses)
    for i in range(1, len(out)):
        left = _LEAVE_IT.match(FILLER.sub("", out[i].text.strip()).strip())
        j = next((j for j in range(i - 1, -1, -1) if not paused(out[j].text)), None)
        if left is None or j is None or out[j].kind is not ClauseKind.REQUEST:
            continue
        way = set(words(out[j].text)) & {"on", "off"}
        if left.group(1).lower() not in ("on", "off") or (way and left.group(1).lower() not in way):
            out[j] = Clause(out[j].text, ClauseKind.NEGATED)
    return out


_WHY_TO = re.compile(r"^(?:so as |in order )?to \w+", re.IGNORECASE)


def _past_why(clauses: list[Clause], text: str) -> list[Clause]:
    """"Primeiro the bathroom, to check the towels, then the bedroom, …": a place said with "then" after
    what a step is for goes on from that step, as it would right after it (text test v104: no bedroom)."""
    out = list(clauses)
    for i in range(2, len(out)):
        step, why, clause = out[i - 2], out[i - 1], out[i]
        if clause.kind is ClauseKind.STATEMENT and fragment(clause.text) and why.kind is ClauseKind.STATEMENT \
                and _WHY_TO.match(why.text.strip()) and step.kind is ClauseKind.REQUEST \
                and _joined(why, clause, text, r"\s*,?\s*(?:and\s+)?then\s+"):
            out[i] = Clause(clause.text, ClauseKind.REQUEST)
    return out


def _goes_there(after: list[Clause]) -> bool:
    """The next clause is a request to go "there": "Robot, the kitchen, you go there" is one step."""
    return bool(after) and after[0].kind is ClauseKind.REQUEST and "there" in words(after[0].text)


# the robot called by name alone, as a clause of its own ("Yo robot, living room")
_ROBOT_ALONE = re.compile(r"^(?:(?:yo|oi|ok|okay|right|now|so|hey|hi)\W+)?(?:robot|jarvis|robbie)\W*$", re.IGNORECASE)
# what one says to the robot by name that names no thing: a greeting, thanks, praise, how it is
_SOCIAL = frozenset({"thanks", "thank", "you", "cheers", "hello", "hi", "hiya", "morning", "evening", "afternoon",
                     "night", "goodnight", "good", "well", "done", "sorry", "okay", "ok", "yes", "no", "please",
                     "dear", "love", "buddy", "mate", "boy", "girl", "job", "there", "here", "again", "friend",
                     "very", "so", "too", "fine", "great", "nice", "lovely", "muy", "bien", "bueno", "molto", "bene",
                     "sehr", "gut", "zoom", "ready", "steady"})


def _after_its_name(clauses: list[Clause]) -> list[Clause]:
    """"Yo robot, living room, my knees are killing me": a place or a person named right after the
    robot is called by name is asked for, as "Living room, please" is (text test v101 left it
    talk); not a greeting or a thanks ("Robot, good morning"), nor a name ("Robot, Anna. Anna, say hello":
    an introduction as likely as a call)."""
    out = list(clauses)
    for i in range(1, len(out)):
        said = FILLER.sub("", out[i].text.strip()).strip()
        named = set(words(said)) - ARTICLES
        if out[i].kind is ClauseKind.STATEMENT and _ROBOT_ALONE.match(out[i - 1].text.strip()) and fragment(said) \
                and named and not named & (_SOCIAL | IMPERATIVES) and not any(w.endswith("ly") for w in named) \
                and not any(a_person(w) for w in said.split() if w.lower() not in ARTICLES) \
                and words(said)[0] != "your" \
                and not any(c.kind is ClauseKind.REQUEST and named <= set(words(c.text)) for c in out[:i]) \
                and not _goes_there(out[i + 1:]):
            out[i] = Clause(out[i].text, ClauseKind.REQUEST)
    return out


_YOU_VERB = re.compile(r"^you (\w+)\b", re.IGNORECASE)


def _either_or(clauses: list[Clause], text: str) -> list[Clause]:
    """"Tell me, you drive to the kitchen alone, or someone must push you?": "you <verb> …" then an
    "or …" and a question mark asks how it does it, as "can you …?" would (text test v73: it drove)."""
    out = list(clauses)
    if not text.rstrip().endswith("?"):
        return out
    for i in range(len(out) - 1):
        said = FILLER.sub("", out[i].text.strip()).strip()
        verb = _YOU_VERB.match(said)
        if out[i].kind is ClauseKind.REQUEST and verb and verb.group(1).lower() in IMPERATIVES \
                and words(out[i + 1].text)[:1] == ["or"]:
            out[i] = Clause(out[i].text, ClauseKind.ABILITY)
    return out


_BARE_NAME = re.compile(r"^(?:and )?[A-Z][a-z]+$")
_CALL_WITH = re.compile(r"\b(?i:call|ring|phone|video|facetime|dial)\b.*\b(?!I\b)[A-Z][a-z]+")


def _said_to(clauses: list[Clause], text: str) -> list[Clause]:
    """"call Anna for me, Tom.": a name said last, after a comma, behind a call that has its person
    already is whom the words were said to, not a second call (audio test v95: "…, tá?" heard so);
    so is one behind a request that is no call ("projector off and go to hallway, Anna": audio test
    v102 heard a Czech "ano", yes, as "Anna", and rang her). Not a room ("…, Kitchen.")."""
    out = list(clauses)
    verb = words(FILLER.sub("", out[-2].text.strip()))[:1] if len(out) > 1 else []
    if len(out) > 1 and out[-1].kind is out[-2].kind is ClauseKind.REQUEST \
            and (name := out[-1].text.strip()) and re.fullmatch(r"(?:(?:Dr\.?|Doctor|Mr|Mrs|Ms) )?[A-Z][a-z]+", name) \
            and not _ROOM_ALONE.fullmatch(name) \
            and (_CALL_WITH.search(out[-2].text) or not set(verb) & _CALLING) \
            and _joined(out[-2], out[-1], text, r"\s*,\s*") and re.search(re.escape(name) + r"\W*$", text):
        out[-1] = Clause(out[-1].text, ClauseKind.STATEMENT)
    return out


def _name_list(clauses: list[Clause], text: str) -> list[Clause]:
    """"go to the living room and Ben, Clara, Anna.": names in a row with only commas between them
    and no verb are a list, no steps (audio test v55: "and then call Anna" heard so, and Ben was
    called). One call at a time is all the robot makes, so which one was meant is not known."""
    out = list(clauses)
    for i in range(1, len(out)):
        before, clause = clauses[i - 1], clauses[i]
        if before.kind is clause.kind is ClauseKind.REQUEST and _BARE_NAME.match(before.text.strip()) \
                and _BARE_NAME.match(clause.text.strip()) and before.text.strip() != clause.text.strip() \
                and _joined(before, clause, text, r"\s*,\s*(?:and\s+)?"):
            out[i - 1] = Clause(before.text, ClauseKind.STATEMENT)
            out[i] = Clause(clause.text, ClauseKind.STATEMENT)
    return out


def _not_that_but(clauses: list[Clause]) -> list[Clause]:
    """"Change of plan, not the kitchen. Living room, and ring Clara …": the place said right after
    "not the X" is the one meant, when nothing follows it or a request does (text test v61); not
    "Not the kitchen. The bathroom, I think, is where I left them.". A room said just before the
    "not the X" is meant too, when the same holds."""
    out = list(clauses)
    for i in range(len(out) - 1):  # … and said before it: "HALLWAY, not living room." (text test v112)
        room, after = out[i], out[i + 2:]
        if room.kind is ClauseKind.STATEMENT and _ROOM_ALONE.fullmatch(room.text.strip()) \
                and out[i + 1].kind is ClauseKind.NEGATED and _NOT_THAT.match(out[i + 1].text.strip()) \
                and (not after or after[0].kind is ClauseKind.REQUEST or words(after[0].text) == words(room.text)):
            out[i] = Clause(room.text, ClauseKind.REQUEST)
    for i in range(1, len(out)):
        said, last = out[i], i + 1 == len(out)
        if said.kind is ClauseKind.STATEMENT and fragment(said.text) and out[i - 1].kind is ClauseKind.NEGATED \
                and _NOT_THAT.match(out[i - 1].text.strip()) and (last or out[i + 1].kind is ClauseKind.REQUEST) \
                and not any(c.kind is ClauseKind.REQUEST and set(words(said.text)) - ARTICLES <= set(words(c.text))
                            for c in out[:i]):  # "Go to the X, not the Y, the X": said again
            out[i] = Clause(said.text, ClauseKind.REQUEST)
    return out


def _own_and(clauses: list[Clause], text: str) -> list[Clause]:
    """"I'll pop the milk in the fridge and leave the key by the front door": the verb after the
    "and" is the speaker's too, no request (text test v58), nor are the fragments that followed it."""
    out = list(clauses)
    for i in range(1, len(out)):
        before, clause = out[i - 1], out[i]
        said = words(clause.text)
        if clause.kind is ClauseKind.REQUEST and before.kind is ClauseKind.STATEMENT and said \
                and said[0] in IMPERATIVES and not _ASKED.search(clause.text) \
                and _OWN_NEXT.match(FILLER.sub("", before.text.strip()).strip()) \
                and _joined(before, clause, text, r"\s+and(?: then)?\s+"):
            out[i] = Clause(clause.text, ClauseKind.STATEMENT)
            for j in range(i + 1, len(out)):
                if out[j].kind is not ClauseKind.REQUEST or not fragment(out[j].text):
                    break
                out[j] = Clause(out[j].text, ClauseKind.STATEMENT)
    return out


def _done_too(clauses: list[Clause], text: str) -> list[Clause]:
    """"I'd like to ring Ben after you've gone into the bedroom and switched the projector on":
    the second thing done ("switched …") is a step too, right after the first ("go into the
    bedroom", `intent.read_request`'s), before the request (text test v54)."""
    for i, clause in enumerate(clauses):
        said = words(clause.text)
        if clause.kind is not ClauseKind.STATEMENT or not said or base_form(said[0]) == said[0] \
                or base_form(said[0]) not in IMPERATIVES:
            continue
        done = re.search(r"\byou(?:'ve| have) (\w+)\b([^.!?]*?),?\s+and\s+" + re.escape(clause.text.strip()), text,
                         re.IGNORECASE)
        first = f"{base_form(done.group(1))}{done.group(2)}".strip().lower() if done else None
        at = next((j for j, c in enumerate(clauses) if c.kind is ClauseKind.REQUEST and c.text.lower() == first), None)
        if at is not None and at < i:
            step = Clause(base_form(said[0]) + clause.text.strip()[len(said[0]):], ClauseKind.REQUEST)
            return [*clauses[:at + 1], step, *[c for k, c in enumerate(clauses) if k > at and k != i]]
    return clauses


_BEFORE_THAT = re.compile(r"^(?:before (?:that|then|you do that|doing that)|beforehand)$", re.IGNORECASE)


def _before_that_last(clauses: list[Clause], text: str) -> list[Clause]:
    """"Turn on the projector - oh, but go to the living room before that": a "before that"
    said after a request, with no request after it, puts that request first (text test v55; said
    before a request, "before that, …" puts the one after it first: `intent.read_request`)."""
    asked = [i for i, c in enumerate(clauses) if c.kind is ClauseKind.REQUEST]
    for i, clause in enumerate(clauses):
        said_at = text.rfind(clause.text.strip())  # the requests all said before it (not "…. Before that, go …")
        if i and _BEFORE_THAT.match(FILLER.sub("", clause.text.strip()).strip()) and asked and asked[0] < i - 1 \
                and clauses[i - 1].kind is ClauseKind.REQUEST \
                and all(text.find(clauses[j].text) < said_at for j in asked) \
                and _joined(clauses[i - 1], clause, text, r"\W+"):
            moved = clauses[i - 1]
            return [*clauses[:asked[0]], moved, *[c for k, c in enumerate(clauses) if k >= asked[0] and k != i - 1]]
    return clauses


def _before_that_both(clauses: list[Clause], text: str) -> list[Clause]:
    """"Call Ben. Before that - go to the living room and switch the projector on.": the request joined
    by "and" to the one "before that" put first goes first with it (text test v108: the call came
    between them)."""
    out = list(clauses)
    for b, clause in enumerate(out):
        if not (_BEFORE_THAT.match(FILLER.sub("", clause.text.strip()).strip()) and b + 1 < len(out)
                and out[b + 1].kind is ClauseKind.REQUEST):
            continue
        first = next((i for i in range(b) if out[i].kind is ClauseKind.REQUEST
                      and _joined(out[i], out[b + 1], text, r"\s*,?\s*and(?: then)?\s+")), None)
        if first is not None and text.find(out[first].text.strip()) > text.find(clause.text.strip()):
            moved = out.pop(b + 1)
            out.insert(first + 1, moved)
        break
    return out


def _joined(before: Clause, clause: Clause, text: str, between: str) -> bool:
    """`before` and `clause` are said one after the other in `text`, with `between` (a pattern) between."""
    return re.search(re.escape(before.text.strip()) + between + re.escape(clause.text.strip()), text) is not None


def _described(text: str) -> bool:
    """A way with no verb of a request of its own and no "you" ("off to the bedroom …"): where
    the robot goes, told, not asked. A bare place ("Bedroom, please.") is still asked."""
    said = words(text)
    return bool(said) and said[0] in _WAYS and "you" not in said and "please" not in said


_WAY_TO = re.compile(r"^(?:into|in to|through to|through into|over to|back to|off to|on to|out to|round to)"
                     r" (?:the|my|your) \w+(?: \w+)?$", re.IGNORECASE)


def tag_asks(before: Clause, tag: str) -> bool:
    """Whether the tag makes the clause before it a request: an ability question that asks with
    it ("would you ever …, please?"), a bare place or thing with "please", "if you would" or
    haste ("Bedroom, please.", "Front door, Jarvis, chop chop": the name between says nothing)."""
    if before.kind is ClauseKind.ABILITY:
        return classify(f"{before.text} {tag.strip()}") is ClauseKind.REQUEST
    way = _WAY_TO.match(before.text.strip())  # "Into the bedroom, mate.": a way, said to the robot (text v66)
    urges = re.search(r"\bplease\b|^\s*if you\b", tag, re.IGNORECASE) or HASTE.match(tag.strip()) or way
    return before.kind is ClauseKind.STATEMENT and (fragment(before.text) or bool(way)) and urges is not None \
        and not LIST_INTRO.match(before.text.strip()) and not BEFORE_THAT.match(before.text.strip())
    # ("Three things, please: …"; "Ring Clara, but before that projector off, please.")
