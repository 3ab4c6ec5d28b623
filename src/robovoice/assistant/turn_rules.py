"""The tool loop's rules for the steps of one turn (`loop.Assistant.turn`): which calls ran,
what is still to do in a compound request, a request only looked up, what a step offers, a repeated look-up, and the
words of a turn the model ended without any, and the history kept between turns."""

from __future__ import annotations

import json
from collections.abc import Collection, Mapping, Sequence

from robovoice.assistant.code_switch import translated
from robovoice.assistant.events import ToolCalled, ToolReturned
from robovoice.assistant.fit import fits, listed, named_whole, names
from robovoice.assistant.gate import NOT_REQUESTED, said_after
from robovoice.assistant.hypothetical import asked_as_question, asks_ever
from robovoice.assistant.lexicon import words
from robovoice.assistant.reading import Clause, ClauseKind, Intent
from robovoice.assistant.speech_guard import claimed_action_in
from robovoice.llm.base import ChatMessage, ToolCallRequested, ToolSpec
from robovoice.manifest.voice import VoiceDecl


def call_key(request: ToolCallRequested) -> str:
    return request.name + json.dumps(request.arguments, sort_keys=True, default=str)


def is_repeat(request: ToolCallRequested, specs: Mapping[str, ToolSpec], looked_up: Collection[str]) -> bool:
    """A read-only call already made with the same arguments, with no action since."""
    spec = specs.get(request.name)
    return spec is not None and spec.read_only and call_key(request) in looked_up


def ran_calls(outcomes: Sequence[ToolReturned]) -> list[ToolReturned]:
    """The calls that reached the robot (the check before acting refused none of them)."""
    return [o for o in outcomes if o.error != NOT_REQUESTED]


def done(outcomes: Sequence[ToolReturned], passed: int = 0) -> int:
    """How many of the things asked are done: the calls that ran, and those the turn moved past
    without one (`passed`: a look-up answered in words, a step whose refused call was made
    again); the next thing asked is `asked[done(...)]`."""
    return len(ran_calls(outcomes)) + passed


def on_the_way(outcome: ToolReturned, read_only: Collection[str], asked: Sequence[str], lookups: Sequence[bool],
               due: int, specs: Sequence[ToolSpec]) -> list[str]:
    """A look-up that ran while the thing asked next names a value an action lists ("get
    yourself into the living room, then …": the model looked up its pose first) does not do
    that thing: it had counted as the step done, and the turn moved on to the projector, the
    drive never made. The actions that thing names (then offered alone, as `unacted`'s), or
    none: the look-up counts as a step ("check your battery and go to the hallway")."""
    if outcome.name not in read_only or outcome.error == NOT_REQUESTED or due >= len(asked) or lookups[due]:
        return []
    return naming(asked[due], specs)


def asked_left(asked: Sequence[str], outcomes: Sequence[ToolReturned], passed: int = 0) -> bool:
    """A compound request with things asked that are not done yet; or a request whose first
    call was refused as what the person declined beside it ("Please don't switch the projector
    on. I only want to talk to Dr. Weber." — told only why, the model left the request undone)."""
    if len(asked) == 1 and len(outcomes) == 1 and not passed and _reason(outcomes[0]) == ClauseKind.NEGATED.value:
        return True
    return len(asked) > 1 and done(outcomes, passed) < len(asked)


def unacted(asked: Sequence[str], lookups: Sequence[bool], specs: Sequence[ToolSpec],
            calls: Sequence[ToolCalled]) -> tuple[str, list[str]] | None:
    """The first thing asked that names, whole, a value an action lists ("wait for me in the hallway":
    a place `navigate_to` takes), when the turn has called look-ups and no action: the small
    model looks up its pose or the camera and answers as if it had gone ("I'm waiting in the
    hallway."). That request, and the actions that list what it names: it is asked for once
    more, offered only those; the check before acting still decides whatever is called then.
    Not a look-up asked for ("tell me about the kitchen"), nor a request said as a question
    ("can you fit through the front door, do you reckon?"): where the reading takes a question
    for a request, the model's own answer is the second check, and pushing it would act."""
    if not calls or {c.name for c in calls} & {s.name for s in specs if not s.read_only}:
        return None
    return _first_naming(asked, lookups, specs)


def _first_naming(asked: Sequence[str], lookups: Sequence[bool],
                  specs: Sequence[ToolSpec]) -> tuple[str, list[str]] | None:
    """The first thing asked, not a look-up, that names a value an action lists, and those actions."""
    return next(((step, acts) for step, lookup in zip(asked, lookups, strict=True)
                 if not lookup and (acts := naming(step, specs))), None)


def claimed_unacted(asked: Sequence[str], lookups: Sequence[bool], specs: Sequence[ToolSpec],
                    text: str, said: object = None) -> tuple[str, list[str]] | None:
    """The model called nothing and answered in words that claim an action ("I am now at the
    kitchen." for "Three jobs. Kitchen first, then ring Ben."): the first thing asked that names
    a value an action lists, and those actions, as `unacted` gives them; it is asked for once
    more, offered only those, and the check before acting still decides. So is a turn the model
    ended with nothing to say ("Kitchen first, and once you're there, switch on the projector."
    read back, which is never spoken: text test v63). None when the words claim nothing: a
    refusal in words is the model's own second check, and is kept, unless the request was said in
    another language (`said`, the person's words: `code_switch.translated`): the small model's
    words then answer what it did not understand ("Zima, hiyo! How can I assist you today?" for
    "Zima hiyo projector", text test v85), so the first thing asked is asked once more, as the
    reading put it in English, offered the actions it names."""
    said_nothing = not text.strip()
    if said_nothing or claimed_action_in(text) is not None:
        return _first_naming(asked, lookups, specs)
    if not isinstance(said, str) or not translated(said):
        return None
    return _first_naming(asked, lookups, specs) or next(
        ((step, acts) for step, lookup in zip(asked, lookups, strict=True)
         if not lookup and not asked_as_question(step)  # a request said as a question keeps the model's answer
         and (acts := [s.name for s in specs if not s.read_only and names(step, s.name, {})])), None)


def naming(step: str, specs: Sequence[ToolSpec]) -> list[str]:
    """The actions that list, as an argument's value, something the step names whole ("the
    hallway": navigate_to); none for a step said as a question (see `unacted`), unless it is a
    "would you ever …" the reading took for the request it is in Ireland (dev ever-4)."""
    if asked_as_question(step) and not asks_ever(step, step):
        return []
    heard = words(step)
    return [s.name for s in specs if not s.read_only and any(
        named_whole(value, s.description, heard) for values in listed(s.parameters).values() for value in values)]


def refit(asked: Sequence[str], outcomes: Sequence[ToolReturned], passed: int, fitting: Collection[str]) -> bool:
    """The only thing asked is still to do after the model's call was refused as not fitting it
    (`refused_for_fit` names what fits): "off you pop and plug yourself in" and the model rang
    the doctor, then, offered the dock, answered "I did not ask for a video call." It is asked
    for once more, offered what fits (a compound request's next step is asked anyway). Not a
    request said as a question: there the model's own answer stays the second check. `asked` as
    the reading words it (`Intent.worded_steps`): a question it put right or resolved ("would
    you come over here to me?" after "I'm in the bathroom") is a plain request there."""
    due = done(outcomes, passed)
    return bool(fitting) and len(asked) == 1 and due == 0 and not asked_as_question(asked[0])


def _refusal_details(outcome: ToolReturned) -> dict[str, object]:
    """The ``details`` of the check before acting's refusal of this call (empty: not refused)."""
    details = outcome.result.get("details") if outcome.error == NOT_REQUESTED and outcome.result is not None else None
    return details if isinstance(details, dict) else {}


def _reason(outcome: ToolReturned) -> str | None:
    """Why the check before acting refused this call (None: it was not refused)."""
    reason = _refusal_details(outcome).get("reason")
    return reason if isinstance(reason, str) else None


def offered(specs: Sequence[ToolSpec], lookup: bool, fitting: Collection[str] = ()) -> list[ToolSpec]:
    """The tools offered on a step: on a compound request's look-up ("tell me where you are,
    then …") only the read-only ones, so nothing acts on it; after a call was refused for
    not fitting the request, the read-only ones and those that fit it (`refused_for_fit`; the
    request asked for once more, `refit`, is offered only those that fit)."""
    return [s for s in specs if s.read_only or not (lookup or (fitting and s.name not in fitting))]


def refused_for_fit(outcomes: Sequence[ToolReturned], due: Sequence[str] = (),
                    voice: Mapping[str, VoiceDecl] | None = None) -> list[str]:
    """The tools that fit the request, named by a refusal of a call that did not (`gate.OTHER`);
    of those, the ones that fit the thing asked next (`due`, its words, when `voice` gives the
    tools' words), if any do: "wind up the call with Anna, then pop the projector on" and the
    model called Anna; offered both tools that fit the request, it did the projector and never
    ended the call (dev `wrapup-1`)."""
    found: list[str] = []
    for o in outcomes:
        named = _refusal_details(o).get("fits")
        if isinstance(named, list):
            found += [name for name in named if isinstance(name, str)]
    if not due or not voice:
        return found
    step = Intent((Clause(due[0], ClauseKind.REQUEST),))
    return [n for n in found if n in voice and fits(step, n, voice[n].words, {})] or found


def wordless_reply(outcomes: Sequence[ToolReturned], read_only: Collection[str]) -> str:
    """What the person hears when the model ended a turn without words: true to what ran."""
    ran = ran_calls(outcomes)
    if not ran:
        reasons = [r for r in map(_reason, outcomes) if r is not None]
        after = said_after(reasons[-1]) if reasons else None
        if after is not None:
            return after
        return "Sorry, I'm not sure what you would like me to do. Could you say it another way?"
    if ran[-1].is_error:
        return "Sorry, that did not work."
    if all(o.name in read_only for o in ran):  # a question: the answer is in a result nobody worded
        return "Sorry, I found the answer but could not put it into words. Please ask me again."
    return "Done."


def bounded_history(messages: Sequence[ChatMessage], limit: int) -> list[ChatMessage]:
    """A conversation's history kept bounded, starting at a user message (tool results stay
    paired), user audio dropped.

    When it outgrows `limit` it is cut to about half, not by one turn: a model server (or the
    embedded model) that reuses the evaluated prompt prefix then only re-evaluates the
    conversation once every few turns, instead of on every turn once the window is full
    (measured in the demo: the first token of a late turn went from 6 s to the usual 1.5-2 s)."""
    history = [m if m.role != "user" else ChatMessage("user", m.text) for m in messages]
    if len(history) > limit:
        history = history[-max(1, limit // 2):]
    while history and history[0].role != "user":
        history.pop(0)
    return history
