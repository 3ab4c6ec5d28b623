"""The check before acting: an actuation tool runs only when the user asked for it now.

Read-only tools (MCP ``readOnlyHint``) always run: looking things up is never an unwanted
action (the robot's stop is refused only where the robot stands still: the loop asks its pose
snapshot, `loop.Assistant._standing_still`). An actuation tool the model calls is refused
locally — it never reaches the robot — when the user's words (`intent.read_request`) asked
for no action at all (a negated or postponed request, an ability question, talk that merely
mentions a place or a person, a request cut off before its object), or when its arguments
name only what the user said *not* to do ("don't call Anna, call Ben": a call to Anna), or
when the request points at something nobody named ("go there", "call her") and the model
filled in a place or a person the conversation never mentioned, or when the tool does not fit
what was asked (`fit`: "plug yourself in" and the projector). The model gets a structured
``not_requested`` tool error whose hint tells it how to answer instead, so the turn still
ends with words the person understands (or, when it has none, `said_after`'s).

Audio given to an audio-capable model has no words to read: nothing is refused then.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Collection, Mapping, Sequence
from typing import Any

from robovoice.assistant.fit import (
    claimed_elsewhere,
    fits,
    fitting_tools,
    glosses,
    listed,
    listed_names,
    named_in,
    named_whole,
    subject_words,
    switches_the_one_thing_off,
    unlisted,
    unsaid,
    usual,
    value_owner,
)
from robovoice.assistant.halting import staying
from robovoice.assistant.lexicon import RELATIONS, words
from robovoice.assistant.polarity import righted, wrong_way
from robovoice.assistant.reading import Clause, ClauseKind, Intent
from robovoice.llm.base import ToolSpec
from robovoice.manifest.voice import VoiceDecl

log = logging.getLogger(__name__)

NOT_REQUESTED = "not_requested"

UNCLEAR = "unclear"  # a reference the conversation does not resolve: "go there", "call her"

OTHER = "other_tool"  # a request stands, but not for this tool: "plug yourself in" and the projector

WRONG_WAY = "wrong_way"  # a switch sent the other way round: "switch the projector off" with on: true

CONFIRM = "confirm"  # held until the person says yes: the words may be misheard (assistant/confirm.py)

_HINTS = {
    ClauseKind.NEGATED.value: "The user asked you not to do this now. Do not do it. Acknowledge in one short "
                              "sentence.",
    ClauseKind.ABILITY.value: "The user only asked whether you can do this, not to do it now. Say in one short "
                              "sentence, in the first person, that you can do it when they ask you to.",
    ClauseKind.STATEMENT.value: "The user did not ask you to do anything; they were telling you something. Reply "
                                "kindly in one short sentence without using tools.",
    ClauseKind.QUESTION.value: "The user asked a question, not for an action. Answer it in one short sentence.",
    ClauseKind.UNFINISHED.value: "The user stopped before saying all of it. Do not guess: ask them in one short "
                                 "question to say it again.",
    UNCLEAR: "The user did not say which one they mean. Do not guess: ask them in one short question.",
    OTHER: "The user did not ask for this tool. Do only what they asked; if you are not sure what that is, "
           "ask them in one short question.",
    WRONG_WAY: "The user asked for the opposite: call the same tool again with the other true/false value.",
    CONFIRM: "The user's words may have been misheard. Do not do it yet: ask them whether they want it.",
}


# What the robot says after a refusal when the model found no words of its own (a small model
# often reads the hint out instead, which is never said): one line per reason, true whatever
# the model had in mind.
_AFTER = {
    ClauseKind.NEGATED.value: "All right, I won't.",
    ClauseKind.STATEMENT.value: "I see.",
    ClauseKind.QUESTION.value: "I'm not sure. Could you ask me another way?",
    ClauseKind.ABILITY.value: "Yes, I can do that when you ask me to.",
    ClauseKind.UNFINISHED.value: "Sorry, I didn't catch all of that. Could you say it again?",
    UNCLEAR: "Which one do you mean?",
    OTHER: "Sorry, I'm not sure what you'd like me to do. Could you say it another way?",
    WRONG_WAY: "Sorry, I got that the wrong way round. Could you say it again?",
    CONFIRM: "I'm not sure I heard you right. Shall I go ahead?",  # the tool's own question is said first
}


def own_words(refused: Mapping[str, Any]) -> str | None:
    """The robot's own words after a refused call, said instead of another model step (which
    on the embedded model tends to make the same call again, or word the refusal oddly): its
    question after a call refused as `UNCLEAR` whose argument lists its values ("Which one do
    you mean: Anna, Ben, Clara or Dr. Weber?") or held for `CONFIRM` ("Shall I call Anna?"),
    and its "yes" to an ability question about that very call (`_about_this`); else None."""
    details = refused.get("details")
    if not isinstance(details, Mapping):
        return None
    if isinstance(answer := details.get("answer"), str):
        return answer
    if details.get("reason") == CONFIRM:
        asked = details.get("question")
        return asked if isinstance(asked, str) else None
    choices = details.get("choices") if details.get("reason") == UNCLEAR else None
    if not isinstance(choices, list) or not choices:
        return None
    named = [str(c) for c in choices]
    return "Which one do you mean: " + (", ".join(named[:-1]) + " or " if len(named) > 1 else "") + named[-1] + "?"


def held(name: str, asked: str) -> dict[str, Any]:
    """The ``{error, message, hint, details}`` body of a call held until the person confirms it:
    it did not reach the robot (scored as refused), and `question` reads the question from it."""
    log.info("held %s until the user confirms: %r", name, asked)
    return {"error": NOT_REQUESTED, "message": f"not done yet: {name} waits for the user's yes",
            "hint": _HINTS[CONFIRM], "details": {"tool": name, "reason": CONFIRM, "question": asked}}


def said_after(reason: str) -> str | None:
    """The robot's own words after a refusal for `reason` (None for a reason it has none for)."""
    return _AFTER.get(reason)


def refusal_reasons() -> tuple[str, ...]:
    """Every ``details.reason`` a refusal can give."""
    return tuple(_HINTS)


def model_only_texts() -> tuple[str, ...]:
    """The hints the gate gives the model: instructions for it, never words for the person
    (`speech_guard.ModelOnlyText` keeps a reply that reads them out from being spoken)."""
    return tuple(_HINTS.values())


_BACK_REFERENCE = re.compile(r"\b(?:it|them|that|one)\b", re.IGNORECASE)


def _siblings(name: str, declared: Mapping[str, Sequence[str]]) -> list[Sequence[str]]:
    """The declared words of the other tools that act on the same thing (start_video_call and
    end_video_call): between them the verb a request opens with says which is meant."""
    subject = subject_words(name)
    return [phrases for tool, phrases in declared.items() if tool != name and subject & subject_words(tool)]


def _names_only_what_was_declined(name: str, intent: Intent, named: Collection[str],
                                  glossed: Collection[str]) -> bool:
    """The tool's own name names a thing the user declined and no request mentions ("leave
    the projector alone" → set_projector_power), which its arguments (a yes/no) cannot show.
    A request that refers back ("don't switch it off, switch it on") may mean the same thing,
    and one that names the call's arguments, or their other names, asks for it ("call Clara -
    no, ring Ben instead"; "don't call the doctor, ring my daughter instead": Anna)."""
    requests = [c for c in intent.clauses if c.kind is ClauseKind.REQUEST]
    if any(_BACK_REFERENCE.search(c.text) for c in requests):
        return False
    if (set(named) | set(glossed)) & {w for c in requests for w in words(c.text)}:
        return False
    return bool(subject_words(name) & intent.negated_words())


def _movers(name: str, voice: Mapping[str, VoiceDecl]) -> list[Sequence[str]]:
    """For the robot's stop and cancel (voice roles "stop", "cancel"): the words of its motion tools."""
    if name not in voice or voice[name].role not in ("stop", "cancel"):
        return []
    return [section.words for section in voice.values() if section.role == "motion"]


def _moves(name: str, voice: Mapping[str, VoiceDecl]) -> bool:
    """A tool that moves the robot or halts it (voice roles "motion", "stop", "cancel"): asked for by a
    request's own words, never through a "turn it off" or "give it a shove" that looks back at
    something named ("… front door sticks, give it a shove", text test v66, drove there)."""
    return name in voice and voice[name].role in ("motion", "stop", "cancel")


def _glossed(spec: ToolSpec | None, arguments: Mapping[str, Any]) -> list[str]:
    """The words of the other names the tool's description gives the call's values ("the loo"
    is the bathroom)."""
    if spec is None:
        return []
    return [w for value in arguments.values() if isinstance(value, str)
            for g in glosses(value, spec.description) for w in words(g)]


def _about_this(intent: Intent, spec: ToolSpec, arguments: Mapping[str, Any], said: Collection[str],
                declared: Mapping[str, Sequence[str]]) -> bool:
    """An ability question about this very call: it says the tool's own words ("could you put
    the projector on by yourself?") and names each listed value the call has ("could you ring
    Clara?"; not "could you phone people abroad?", made a call to Anna). The robot's own "yes"
    answers it: the embedded model, asked to word it, said "I can't do that right now" or "You
    can go back to your charger alone". Otherwise the model answers; it may know the robot
    cannot (texts, stairs)."""
    return bool(declared.get(spec.name)) and _fits(
        intent, spec.name, arguments, said, declared, _glossed(spec, arguments), (ClauseKind.ABILITY,)
    ) and not unsaid(spec.description, spec.parameters, arguments, [*said, *intent.words()])


def _fits(intent: Intent, name: str, arguments: Mapping[str, Any], said: Collection[str],
          declared: Mapping[str, Sequence[str]], glossed: Sequence[str],
          kinds: Collection[ClauseKind] = (ClauseKind.REQUEST,), movers: Sequence[Sequence[str]] = (),
          pooled: bool = True) -> bool:
    """`fit.fits` for this call, with its rivals and what the other tools act on taken from
    every tool's declared words. `movers`: the words of the tools that move the robot, rivals of
    its stop and cancel: "go and wait by the front door" opens with the drive, and its "wait" is
    what to do there (text test v20: the robot's stop ran before the drive)."""
    elsewhere = [w for tool in declared if tool != name for w in subject_words(tool)]
    return fits(intent, name, declared.get(name, ()), arguments, said, [*_siblings(name, declared), *movers],
                glossed, elsewhere, kinds, pooled=pooled)


def _asked_by_value(intent: Intent, tools: Sequence[ToolSpec], declared: Mapping[str, Sequence[str]], but: str,
                    said: Collection[str]) -> list[str]:
    """The actions, other than `but`, that a request asks for by one of their listed values alone
    ("Front door, quickly, somebody is ringing!": the drive, though no word of it was said; the
    model rang Anna, and told only that nobody asked for that, it did nothing: text test v111)."""
    return [t.name for t in tools if t.name != but and not t.read_only and any(
        _fits(intent, t.name, {arg: v}, said, declared, ()) for arg, values in listed(t.parameters).items()
        for v in values)]


def _listed_values(spec: ToolSpec, arguments: Mapping[str, Any]) -> dict[str, str]:
    """The call's arguments whose values the tool lists (a place, a contact)."""
    choices = listed(spec.parameters)
    return {arg: v for arg, v in arguments.items() if arg in choices and isinstance(v, str)}


def _fitting_words(intent: Intent, spec: ToolSpec, arguments: Mapping[str, Any], said: Collection[str],
                   declared: Mapping[str, Sequence[str]], requests: Sequence[Clause]) -> list[str]:
    """The words of those `requests` that this call's words fit, each request read alone."""
    return [w for c in requests if _fits(Intent((Clause(c.text, c.kind),), intent.answering), spec.name, arguments,
                                         said, declared, _glossed(spec, arguments), pooled=False)
            for w in words(c.text)]


def _names_another(spec: ToolSpec, arg: str, value: str, heard: Sequence[str]) -> bool:
    """`heard` names another of the values the tool lists for `arg` ("your dock" names the dock)."""
    return any(named_whole(other, spec.description, heard)
               for other in listed(spec.parameters)[arg] if other.lower() != value.lower())


def _another_asked(intent: Intent, spec: ToolSpec, arguments: Mapping[str, Any], said: Collection[str],
                   declared: Mapping[str, Sequence[str]]) -> bool:
    """Of the requests, those this call's words fit name another of its listed values and
    not its own: "Hang up with Anna, then call Doctor Weber" asks the call for Dr. Weber; Anna is
    named only in the request to end the call (text test v95: the model rang Anna too). (Not for a
    drive: "nip to the kitchen and then come back to the bathroom when I shout" asks both.)"""
    requests = [c for c in intent.clauses if c.kind is ClauseKind.REQUEST]
    values = _listed_values(spec, arguments)
    if not requests or not values:  # (one request too: "Call Clara, Ben." rang Ben, audio test v102)
        return False
    fitting = _fitting_words(intent, spec, arguments, said, declared, requests)
    return bool(fitting) and any(
        unsaid(spec.description, spec.parameters, {arg: value}, fitting) and _names_another(spec, arg, value, fitting)
        for arg, value in values.items())


# A clause with a subject or a verb of being, a sentence of its own: not a place said bare, which
# may be a step the reading missed ("Then, er, the front door", "from kitchen to bedroom")
_SENTENCE = re.compile(r"\b(?:i|you|he|she|it|we|they|there|this|that|someone|somebody|who)\b|\w'(?:s|re|m|ve|ll|d)\b"
                       r"|\b(?:is|are|was|were|am|been|has|have|had|does|did)\b", re.IGNORECASE)


def _named_in_talk(intent: Intent, spec: ToolSpec, arguments: Mapping[str, Any], said: Collection[str],
                   declared: Mapping[str, Sequence[str]]) -> bool:
    """This call's listed value is named only in talk, and the requests its words fit name another of
    its values: "Go to the kitchen, Ben is in the bedroom" and a drive to the bedroom; "Go charge,
    you're near bed" (text test v97: a drive to the bedroom let through)."""
    values = _listed_values(spec, arguments)
    requests = [c for c in intent.clauses if c.kind is ClauseKind.REQUEST]
    talk = [w for c in intent.clauses if c.kind is ClauseKind.STATEMENT and _SENTENCE.search(c.text)
            for w in words(c.text)]
    if not values or not requests or not talk:
        return False
    asked = [w for c in requests for w in words(c.text)]
    fitting = _fitting_words(intent, spec, arguments, said, declared, requests)
    return any(unsaid(spec.description, spec.parameters, {arg: value}, asked)
               and not unsaid(spec.description, spec.parameters, {arg: value}, talk)
               and _names_another(spec, arg, value, fitting) for arg, value in values.items())


def _only_talk(intent: Intent, why: str | None) -> bool:
    """A call refused as declined or as talk where every clause declines or is talk (no request,
    question or ability question): the robot's own line ("All right, I won't.", "I see.") answers
    at once. The model, asked to word it, took 5-7 s on the embedded model and was mostly given
    that line anyway: in text tests v71 and v72 the first sentence came 8.5-9.6 s (median) after
    negations and mentions against 3.4-4.1 s after single requests, and 12 of the 13 mentions whose
    every call was refused ended with "I see."."""
    return why in (ClauseKind.NEGATED.value, ClauseKind.STATEMENT.value) and all(
        c.kind in (ClauseKind.NEGATED, ClauseKind.STATEMENT) for c in intent.clauses)


def refusal(
    intent: Intent | None, spec: ToolSpec | None, arguments: Mapping[str, Any], said: Collection[str] = (),
    voice: Mapping[str, VoiceDecl] | None = None, *, doubtful: bool = False, tools: Sequence[ToolSpec] = (),
) -> dict[str, Any] | None:
    """The ``{error, message, hint, details}`` body that refuses this call, or None to let it run.
    `said`: the words of the conversation so far (what a "there" or a "her" can refer to);
    `voice`: the tools' voice sections (the words a request for each uses, `fit`); `doubtful`:
    the words may be misheard (a value the tool does not list is then asked about); `tools`:
    every tool offered (the values the others list: whose "screen" a request with "Ben" means)."""
    if intent is None or (spec is not None and spec.read_only):
        return None
    name = spec.name if spec is not None else "?"
    declared = {tool: section.words for tool, section in (voice or {}).items()}
    kind = intent.refusal
    why = kind.value if kind is not None else None
    owner: str | None = None  # the other tool that lists this call's value (a drive to "Ben": the call)
    if why is None:
        values = {t.name: listed_names(t.description, t.parameters) for t in tools}  # what each tool lists
        owner = value_owner(name, spec.parameters, arguments, values) if spec is not None else None
        if owner is not None and (voice or {}).get(owner, VoiceDecl()).role == "motion":
            owner = None  # a call to "the kitchen" is the robot's own error: the model is never pointed at a drive
        named = [w for value in arguments.values() if isinstance(value, str) for w in words(value)]
        heard = [*said, *intent.words()]  # what a "there", a "her" or a listed value can refer to
        glossed = _glossed(spec, arguments)  # the values' other names: "the loo" is the bathroom
        if named and set(named) <= intent.negated_words():
            why = ClauseKind.NEGATED.value
        elif _names_only_what_was_declined(name, intent, named, glossed):
            why = ClauseKind.NEGATED.value  # "leave the projector alone, but come here": the projector
        elif named and intent.refers and not RELATIONS & usual(heard) and not named_in(
                [*named, *glossed], heard):
            # "call her": nobody in the conversation is her ("the doctor" is Dr. Weber; "my
            # daughter" is someone the robot's contacts say, which the model can look up)
            why = UNCLEAR
        elif spec is not None and switches_the_one_thing_off(
                intent, name, arguments, said, {t.name: t.parameters for t in tools if not t.read_only}):
            return None  # "turn it off": the one thing it can switch
        elif not _fits(staying(intent) if (movers := _movers(name, voice or {})) else intent, name, arguments,
                       said, declared, glossed, movers=movers, pooled=not _moves(name, voice or {})) or \
                claimed_elsewhere(intent, name, arguments, declared, values, said) or owner:
            why = OTHER  # "plug yourself in" and the projector; "get Ben up on the screen" and the projector
        elif spec is not None and unsaid(spec.description, spec.parameters, arguments, heard):
            why = UNCLEAR  # "get car on a video call": Anna is nobody's guess to make
        elif doubtful and spec is not None and unlisted(spec.parameters, arguments):
            why = UNCLEAR  # "ring gunner", misheard: which one it knows, not a question about "Gunner"
        elif spec is not None and wrong_way(intent, name, spec.parameters, arguments, declared.get(name, ())):
            why = WRONG_WAY  # "turn the projector off" with on: true (`polarity`)
        elif spec is not None and not _moves(name, voice or {}) and _another_asked(intent, spec, arguments, said,
                                                                                 declared):
            why = OTHER  # "hang up with Anna, then call Doctor Weber": the call asked is Dr. Weber's
        elif spec is not None and _named_in_talk(intent, spec, arguments, said, declared):
            why = OTHER  # "go to the kitchen, Ben is in the bedroom": the drive asked is to the kitchen
        else:
            return None
    answer = _only_talk(intent, why) or (why == ClauseKind.ABILITY.value and spec is not None
                                             and _about_this(intent, spec, arguments, said, declared))
    log.info("refused %s%s: the user did not ask for it (%s)", name, dict(arguments), why)
    others = sorted({*(fitting_tools(intent, declared, name) or _asked_by_value(intent, tools, declared, name, said)),
                     *([owner] if owner else [])}) if why == OTHER else []
    hint = _HINTS[why] + (f" What they asked for fits {' or '.join(others)}." if others else "")
    # the values the person can choose from, for the question `question` asks
    choices = [v for arg, values in listed(spec.parameters).items() if arg in arguments
               for v in values] if why == UNCLEAR and spec is not None else []
    return {
        "error": NOT_REQUESTED,
        "message": f"not done: the user did not ask for {name} now ({why})",
        "hint": hint,
        "details": {"tool": name, "reason": why, **({"fits": others} if others else {}),
                    **({"choices": choices} if choices else {}),
                    **({"answer": _AFTER[str(why)]} if answer else {})},
    }


def checked(
    intent: Intent | None, spec: ToolSpec | None, arguments: Mapping[str, Any], said: Collection[str] = (),
    voice: Mapping[str, VoiceDecl] | None = None, *, doubtful: bool = False, tools: Sequence[ToolSpec] = (),
) -> tuple[dict[str, Any], dict[str, Any] | None]:
    """The arguments to send and the body refusing them (None: they run), as `refusal` decides. A
    switch the model sent the wrong way round ("pakipatay po ng projector", "projector bandh kar
    do" with on: true) is sent the way the words say when the check lets that run: the person
    asked for it, and "Sorry, I got that the wrong way round. Could you say it again?" made them
    say it twice (text tests v76, v77; the model, told to send the other value, seldom did)."""
    refused = refusal(intent, spec, arguments, said, voice, doubtful=doubtful, tools=tools)
    if refused is None or intent is None or spec is None or refused["details"].get("reason") != WRONG_WAY:
        return dict(arguments), refused
    declared = (voice or {}).get(spec.name)
    right = righted(intent, spec.name, spec.parameters, arguments, declared.words if declared is not None else ())
    if right is None or refusal(intent, spec, right, said, voice, doubtful=doubtful, tools=tools) is not None:
        return dict(arguments), refused
    log.info("sending %s%s the way the words say: %s", spec.name, dict(arguments), right)
    return right, None
