"""A tool's own phrase as the spoken answer, instead of a second model step.

After a tool returns, the model is usually asked again only to word what happened: on the
embedded model that is 1-2 s, and the wording often adds facts the result does not hold.
When the tool's manifest declares a `success` (or `failure`) phrase and it fills completely
from the call's arguments and the structured result (`manifest.voice.fill`), the phrase is
the answer to that step (docs/voice.md, "Spoken results"). It is used only when:

- the person asked nothing (no clause of theirs is a question or an ability question, as
  `intent.read_request` reads it): a question about the result ("how far was it?") gets
  the model, which has the result in front of it;
- every call of the step has a phrase that fills: a call refused before it ran, a call with
  arguments the model must correct, or a robot that could not be reached gets the model,
  which has a hint for each;
- no call of the step is read-only: the model often looks something up (the battery, where
  the robot is) before it acts, and a phrase would end the turn before the action.

A step whose every call was refused because the person named none of the values its argument
lists ("put me on a video call") is answered by the robot's own question, which names them
(`gate.own_words`): the model, asked again, tends to make the same call once more. So is an
ability question about the very call the model made ("could you ring Clara?"): "Yes, I can do
that when you ask me to."

A step of look-ups only is said by its phrases, question or not, while the turn goes on with
more the person asked (`continuing`): the look-up was one of the things asked ("tell me where
you are, then come here"), its phrase says what was found, and nothing ends there.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence

from robovoice.assistant.events import ToolCalled, ToolReturned
from robovoice.assistant.gate import NOT_REQUESTED, UNCLEAR, own_words
from robovoice.assistant.reading import ClauseKind, Intent
from robovoice.manifest.voice import VoiceDecl, fill, result_fields

# Errors the assistant itself makes up, not the robot's: the model must answer them (their hints).
_NOT_THE_ROBOTS = frozenset({NOT_REQUESTED, "invalid_arguments", "tool_unavailable"})


def result_phrase(decl: VoiceDecl | None, called: ToolCalled, returned: ToolReturned) -> str | None:
    """The tool's success or failure phrase filled from this call and its result, or None."""
    if decl is None or (returned.is_error and returned.error in _NOT_THE_ROBOTS):
        return None
    template = decl.say.failure if returned.is_error else decl.say.success
    return fill(template, result_fields(called.arguments, returned.result))


def asks_nothing(intent: Intent | None) -> bool:
    """The person's words ask no question: a tool's phrase can answer them. Audio given to an
    audio model has no words to read (None): the model answers."""
    if intent is None:
        return False
    return not any(c.kind in (ClauseKind.QUESTION, ClauseKind.ABILITY) for c in intent.clauses)


def phrase_answer(
    intent: Intent | None, voice: Mapping[str, VoiceDecl], step: Sequence[tuple[ToolCalled, ToolReturned]],
    read_only: Collection[str] = (), *, continuing: bool = False,
) -> str | None:
    """The words that answer one model step's tool calls without the model, or None when
    the model must word the answer (see the module docstring). `read_only`: the names of the
    read-only tools; `continuing`: the turn goes on with more the person asked."""
    if not step or intent is None:
        return None
    own = [own_words(r.result) for _, r in step if r.error == NOT_REQUESTED and r.result is not None]
    if not continuing and len(own) == len(step) and own[-1] is not None:
        return own[-1]  # every call refused, the last with the robot's own words: which one, or yes it can
    looked_up = all(called.name in read_only for called, _ in step)
    if not (continuing and looked_up) and (not asks_nothing(intent) or any(c.name in read_only for c, _ in step)):
        return None
    phrases = _filled(voice, step)
    return " ".join(phrases) if phrases is not None else None


def robot_failed(returned: ToolReturned) -> bool:
    """The robot could not do the call (an unknown place, a closed door), as opposed to a call
    the assistant itself refused or could not make."""
    return returned.is_error and returned.error not in _NOT_THE_ROBOTS


def owed_question(outcomes: Sequence[ToolReturned]) -> str | None:
    """The robot's own "Which one do you mean: …?" when the turn's last call was refused for
    naming nobody it lists, and the turn went on past it (a compound request's next step, where
    the model's words were a repeat): otherwise nobody asks it ("ring gunner", audio v16)."""
    last = outcomes[-1] if outcomes else None
    if last is None or last.error != NOT_REQUESTED or last.result is None:
        return None
    details = last.result.get("details")
    return own_words(last.result) if isinstance(details, dict) and details.get("reason") == UNCLEAR else None


def found_phrase(
    voice: Mapping[str, VoiceDecl], calls: Sequence[ToolCalled], outcomes: Sequence[ToolReturned],
    read_only: Collection[str],
) -> str | None:
    """What the turn's look-ups found, in their own phrases, for a turn the model left without
    words it may say (none, or only words the speech guard held back: a battery level it made
    up after looking the real one up). None when an action ran, a look-up failed or has no
    phrase that fills: then `turn_rules.wordless_reply` answers."""
    ran = [(c, r) for c, r in zip(calls, outcomes, strict=True) if r.error != NOT_REQUESTED]
    if not ran or any(c.name not in read_only or r.is_error for c, r in ran):
        return None
    phrases = _filled(voice, ran)
    return " ".join(dict.fromkeys(phrases)) if phrases is not None else None  # a repeated look-up once


def _filled(voice: Mapping[str, VoiceDecl], calls: Sequence[tuple[ToolCalled, ToolReturned]]) -> list[str] | None:
    """Each call's phrase, or None when any has none that fills."""
    phrases = [result_phrase(voice.get(called.name), called, returned) for called, returned in calls]
    return [p for p in phrases if p is not None] if all(p is not None for p in phrases) else None
