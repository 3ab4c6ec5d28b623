"""The conversation loop: model → tool calls → results back → model, one turn at a time.

Text the model streams is split into sentences as it arrives and each complete sentence is
handed on at once (`model_step`), so speech can start while the model still generates.
A call held for the person's yes (`confirm`) is answered in the next turn without a model step.
Robot-side tool errors go back to the model as tool results so it can recover (ask the user,
list the places). When no backend answers, the turn ends with the spoken fallback message.
"""

from __future__ import annotations

import dataclasses
import json
import logging
from collections.abc import Awaitable, Callable, Mapping, Sequence
from dataclasses import dataclass

from robovoice.assistant import turn_rules
from robovoice.assistant.confirm import DECLINED, Confirmations, Held, confirm_question
from robovoice.assistant.events import (
    BackendFailed,
    ToolCalled,
    ToolProgressed,
    ToolReturned,
    TurnEvent,
    TurnFinished,
    TurnStarted,
    notify,
)
from robovoice.assistant.gate import NOT_REQUESTED, checked, held
from robovoice.assistant.halting import halts
from robovoice.assistant.intent import read_request
from robovoice.assistant.lexicon import words
from robovoice.assistant.metrics import TurnMetrics
from robovoice.assistant.model_step import Emit, model_step, say
from robovoice.assistant.motion_probe import PoseMotionProbe
from robovoice.assistant.phrase import found_phrase, owed_question, phrase_answer, result_phrase, robot_failed
from robovoice.assistant.prompt import GUESSED_HINT, SYSTEM_PROMPT, step_hint
from robovoice.assistant.reading import Intent
from robovoice.assistant.robot_tools import Toolbox, ToolOutcome
from robovoice.assistant.speech_guard import MODEL_ONLY, TurnActions
from robovoice.assistant.turn_rules import asked_left, call_key, done, offered, wordless_reply
from robovoice.errors import LLMError
from robovoice.llm.base import ChatMessage, ContentPart, LLMBackend, ToolCallRequested, ToolSpec
from robovoice.llm.failover import FALLBACK_MESSAGE
from robovoice.manifest.voice import VoiceDecl, tools_with_role

log = logging.getLogger(__name__)

Observer = Callable[[TurnEvent], Awaitable[None] | None]


@dataclass(frozen=True, slots=True)
class TurnResult:
    reply: str
    calls: tuple[ToolCalled, ...]
    outcomes: tuple[ToolReturned, ...]
    metrics: TurnMetrics
    fell_back: bool = False


class Assistant:
    """A conversation with the robot's tools. One instance per conversation."""

    def __init__(
        self,
        backend: LLMBackend,
        tools: Toolbox,
        *,
        system_prompt: str = SYSTEM_PROMPT,
        max_steps: int = 4,
        max_history_messages: int = 12,
        observer: Observer | None = None,
        fallback_message: str = FALLBACK_MESSAGE,
        checks: bool = True,  # False: no check before acting nor held call (the benchmark's "without the checks")
    ) -> None:
        if max_steps < 1:
            raise ValueError("max_steps must be at least 1")
        self.backend, self.tools, self.system_prompt, self.checks = backend, tools, system_prompt, checks
        self.max_steps, self.max_history_messages = max_steps, max_history_messages
        self.fallback_message = fallback_message
        self._observer = observer
        self._history: list[ChatMessage] = []
        self.confirmations = Confirmations()  # a call held until the person says yes (assistant/confirm.py)

    def reset(self) -> None:
        """Forget the conversation (a fresh one per evaluation case)."""
        self._history.clear()
        self.confirmations.clear()

    @property
    def history(self) -> Sequence[ChatMessage]:
        return tuple(self._history)

    def _emitter(self, observer: Observer | None) -> Emit:
        """The turn's observer: the conversation's own (constructor), then the turn's."""
        own = self._observer

        async def emit(event: TurnEvent) -> None:
            await notify(own, event)
            await notify(observer, event)

        return emit

    async def turn(
        self,
        user: str | tuple[ContentPart, ...],
        *,
        metrics: TurnMetrics | None = None,
        observer: Observer | None = None,
        doubtful: bool = False,
    ) -> TurnResult:
        """Run one user turn to its spoken reply. `observer` gets this turn's events (after
        the conversation's observer): a voice turn routes its sentences to speech with it.
        `doubtful`: the words may be misheard (a transcript in doubt): a tool that declares a
        confirm question is asked about instead of run (assistant/confirm.py)."""
        metrics = metrics or TurnMetrics()
        emit = self._emitter(observer)
        await emit(TurnStarted(ChatMessage("user", user).text))
        answered = self.confirmations.take(user if isinstance(user, str) else "")
        if answered is not None:  # "Yes, please." to "Shall I call Anna?": no model step
            return await self._answer_held(ChatMessage("user", user).text, *answered, metrics, emit)
        messages, intent = self._opening(user)
        asked, worded = (intent.steps, intent.worded_steps) if intent is not None else ((), ())  # worded: hints, naming
        lookups = intent.lookups if intent is not None else ()
        # things asked the turn moved past without a call that ran: a look-up of a compound request
        # the model answered in words, a step whose refused call the model made again
        passed = 0
        # what a "there" or a "her" can refer to: what the person and the robot said before
        said = {w for m in self._history if m.role in ("user", "assistant") for w in words(m.text)}
        max_steps = max(self.max_steps, len(asked) + 2)
        replies: list[str] = []
        calls: list[ToolCalled] = []
        outcomes: list[ToolReturned] = []
        stepped: list[ToolReturned] = []  # the outcomes that count towards the things asked (`on_the_way`)
        fell_back = False
        steps = 0
        looked_up: set[str] = set()  # read-only calls (name and arguments) made since the last action
        refused: set[str] = set()  # calls (name and arguments) the check before acting refused this turn
        acted = ""  # the last action that ran and did not fail (made again next: not run again)
        answer_now = resume = False  # resume: a step the robot could not do is said before the next
        model_only = MODEL_ONLY.copy()  # what is never said: the prompt, hints, this turn's tool hints
        for tool in (tools := await self.tools.specs()):  # and their descriptions (a small model reads them back)
            model_only.add(tool.description, short_copies=False)
        if isinstance(user, str):  # nor the person's own words read back to them ("Dr. Weber told me I ought to…")
            model_only.add(user, short_copies=False)
        read_only = {s.name for s in tools if s.read_only}
        actuators = {s.name for s in tools if not s.read_only}
        retried = lookup_only = False  # asked again after a guessed figure / this step offers only look-ups
        nudged = False  # a request only looked up was asked for once more (`unacted`)
        fitting: list[str] = []  # after a call that did not fit the request: the tools that do
        only: list[str] = []  # a request only looked up, asked again: the actions it names, alone

        def next_step() -> ChatMessage:  # the hint for the next thing asked (docs/llm.md)
            due = done(stepped, passed)
            return ChatMessage("user", step_hint(worded[due], lookups[due], first=False))

        for step in range(max_steps):
            steps = step + 1
            # On the last step the model gets no tools, so the turn ends with words, not a call.
            offer = step < max_steps - 1 and not answer_now
            specs: list[ToolSpec] = await self.tools.specs() if offer else []
            lookup = asked_left(asked, stepped, passed) and lookups[done(stepped, passed)]
            narrowed = bool(only or fitting) or lookup or lookup_only  # this step offers some tools only
            specs = [s for s in specs if s.name in only] if only else offered(specs, lookup or lookup_only, fitting)
            lookup_only, fitting, only = False, [], []
            try:
                text, requested, guessed = await model_step(self.backend, messages, specs, metrics, emit, model_only,
                                                            TurnActions(calls, outcomes, read_only, actuators))
            except LLMError as exc:
                log.warning("no LLM backend answered: %s", exc)
                fell_back = True
                await emit(BackendFailed(str(exc), self.fallback_message))
                await say(self.fallback_message, metrics, emit)
                replies.append(self.fallback_message)
                break
            if requested and not specs:  # a call written as text on the no-tools step: not run
                log.info("the model called %s on a step that offers no tools; not run", [r.name for r in requested])
                requested = []
            by_name = {spec.name: spec for spec in specs}
            if specs and narrowed and any(r.name not in by_name for r in requested):
                # a call to a tool this step did not offer (a server need not keep to the offer)
                log.info("the model called %s, not offered on this step; not run", [r.name for r in requested])
                requested = [r for r in requested if r.name in by_name]
            if requested and all(turn_rules.is_repeat(r, by_name, looked_up) for r in requested):
                # the same look-up again: its result is already in front of the model (a small
                # model on a strict call grammar repeats it until tools are withdrawn). The
                # repeat is not run; the model answers now, or does the next thing asked.
                log.info("the model repeated %s; not run", [r.name for r in requested])
                requested = []
                if not text:
                    answer_now = not asked_left(asked, stepped, passed)
                    continue
            if requested and all(call_key(r) in refused or call_key(r) == acted for r in requested):
                # a call refused already, or the action just done, made again: not run, and its step
                # is passed over, so a garbled step ("join the project to look") does not keep the next
                # ones from being done, and "go on then, off to the bedroom" drives there once
                log.info("the model made the refused or done %s again; not run", [r.name for r in requested])
                redone, requested, passed = call_key(requested[0]) == acted, [], passed + 1
                if not text:
                    if asked_left(asked, stepped, passed):
                        messages.append(next_step())
                    elif redone and replies:  # what was done is said already
                        break
                    else:
                        answer_now = True
                    continue
            if text:
                replies.append(text)
            if guessed and not requested and not retried and any(s.read_only for s in specs) and not looked_up:
                # a figure nobody gave the model (held back): asked once more, offered only the look-ups
                retried = lookup_only = True
                messages.extend([ChatMessage("assistant", text)] if text else [])
                messages.append(ChatMessage("user", GUESSED_HINT))
                continue
            messages.append(ChatMessage("assistant", text, tuple(c.to_history() for c in requested)))
            if not requested and resume:  # the failure said: on to the next thing asked
                answer_now = resume = False
                messages.append(next_step())
                continue
            if not requested and lookup and text and step < max_steps - 2:
                # the look-up answered in words: the next thing asked is still to do
                passed += 1
                if asked_left(asked, stepped, passed):
                    messages.append(next_step())
                    continue
            if not requested and not (calls or nudged) and step < max_steps - 2 and (
                    left := turn_rules.claimed_unacted(worded, lookups, tools, text, user)) is not None:
                nudged, only = True, left[1]  # "I am now at the kitchen." (or nothing) with no call: asked once more
                messages.append(ChatMessage("user", step_hint(left[0], False, first=False)))
                continue
            if not requested:
                break
            ran: list[tuple[ToolCalled, ToolReturned]] = []
            for request in requested:
                spec = by_name.get(request.name)
                called, returned = await self._run_tool(request, metrics, emit, intent, spec, said, doubtful)
                ran.append((called, returned))
                if returned.error == NOT_REQUESTED:
                    refused.add(call_key(request))
                messages.append(ChatMessage("tool", returned.text, tool_call_id=request.id, name=request.name))
                if spec is not None and spec.read_only:
                    looked_up.add(call_key(request))
                else:
                    looked_up.clear()  # an action may change what a look-up returns
                    acted = "" if returned.is_error else call_key(request)
            calls.extend(c for c, _ in ran)
            outcomes.extend(r for _, r in ran)
            aside: list[str] = []  # the actions a thing asked names, when a look-up ran on the way to it
            for _, r in ran:  # a look-up on the way to a place or a person asked: that is still to do
                if way := turn_rules.on_the_way(r, read_only, asked, lookups, done(stepped, passed), tools):
                    aside = way
                else:
                    stepped.append(r)
            fitting = turn_rules.refused_for_fit([r for _, r in ran], asked[done(stepped, passed):], self.tools.voice())
            for _, r in ran:  # a tool error's hint is for the model: never read out
                hint = r.result.get("hint") if r.is_error and r.result is not None else None
                if isinstance(hint, str):
                    model_only.add_hint(hint)
            more = asked_left(asked, stepped, passed) and step < max_steps - 2
            # only looked up, though a listed place or person was asked (not after words alone: `unacted`)
            left = None if more or nudged or step >= max_steps - 2 else \
                turn_rules.unacted(worded, lookups, tools, calls)
            # the call did not fit what was asked: the request is asked for once more, offered what fits
            # (as worded: "come over here to me?" after "I'm in the bathroom" is "come to the bathroom")
            again = not (more or nudged or left is not None) and step < max_steps - 2 and turn_rules.refit(
                worded, stepped, passed, fitting)
            nudged = nudged or again
            more = more or left is not None or again
            # the tool's own phrase answers this step when it fills and nothing was asked it
            # does not answer: no model step just to word it (assistant/phrase.py)
            # (a look-up's phrase too when more is asked: the turn goes on, and the person hears
            # what was found before the robot moves on)
            phrase = phrase_answer(intent, self.tools.voice(), ran, {s.name for s in specs if s.read_only},
                                   continuing=more)
            if phrase is not None:
                await say(phrase, metrics, emit)
                replies.append(phrase)
                messages.append(ChatMessage("assistant", phrase))
                model_only.add_said(phrase)  # said: the model saying it again is not
                if not more:
                    metrics.mark("phrase_answer")
                    break
            if left is not None:  # only looked up: the request itself is asked for once more
                nudged, only = True, left[1]
                messages.append(ChatMessage("user", step_hint(left[0], False, first=False)))
            elif more and phrase is None and any(robot_failed(r) for _, r in ran):
                answer_now = resume = True  # what the robot could not do is said (by the model) first
            elif more:
                # a compound request: the small model tends to answer after the first call, so it
                # is told which of the things the user asked comes next (after a look-up on the
                # way to it, offered only the actions it names: told alone, it looked up again)
                messages.append(next_step())
                only = aside or (fitting if again else [])  # asked once more: offered only what fits
        held_now = self.confirmations.held  # a call held this turn, or "which one?": the last thing said
        question = held_now.question if held_now is not None else owed_question(outcomes)
        if question is not None and not any(question in r for r in replies):
            await say(question, metrics, emit)
            replies.append(question)
            messages.append(ChatMessage("assistant", question))
        if not fell_back and not any(r.strip() for r in replies):  # the person always hears an answer
            words_ = found_phrase(self.tools.voice(), calls, outcomes, read_only) or wordless_reply(outcomes, read_only)
            log.info("the model ended the turn without words; said %r", words_)
            await say(words_, metrics, emit)
            replies.append(words_)
            messages.append(ChatMessage("assistant", words_))
        reply = " ".join(r.strip() for r in replies if r.strip())
        if not fell_back:
            self._remember(messages[1:])
        metrics.mark("finished")
        await emit(TurnFinished(reply, tuple(calls), steps))
        return TurnResult(reply, tuple(calls), tuple(outcomes), metrics, fell_back)

    async def _answer_held(self, user: str, call: Held, yes: bool, metrics: TurnMetrics, emit: Emit) -> TurnResult:
        """The person's yes or no to a held call: it runs (unchecked: they confirmed it) with its
        phrase as the answer, or it is dropped. No model step either way."""
        messages = [ChatMessage("user", user)]
        calls: tuple[ToolCalled, ...] = ()
        outcomes: tuple[ToolReturned, ...] = ()
        reply = DECLINED
        if yes:
            specs = {s.name: s for s in await self.tools.specs()}
            request = dataclasses.replace(call.request, id=f"{call.request.id}_confirmed")
            called, returned = await self._run_tool(request, metrics, emit, None, specs.get(request.name), set())
            calls, outcomes = (called,), (returned,)
            reply = result_phrase(self.tools.voice().get(request.name), called, returned) or wordless_reply(
                outcomes, {n for n, s in specs.items() if s.read_only})
            messages += [ChatMessage("assistant", "", (request.to_history(),)),
                         ChatMessage("tool", returned.text, tool_call_id=request.id, name=request.name)]
        await say(reply, metrics, emit)
        self._remember([*self._history, *messages, ChatMessage("assistant", reply)])
        metrics.mark("finished")
        await emit(TurnFinished(reply, calls, 0))
        return TurnResult(reply, calls, outcomes, metrics)

    async def first_request(self, text: str) -> tuple[list[ChatMessage], list[ToolSpec]]:
        """The messages and tools the first model step of a turn for `text` would send (the
        same code path as `turn`), without touching the history: for a speculative prefill."""
        messages, intent = self._opening(text)
        lookup = intent is not None and len(intent.steps) > 1 and intent.lookups[0]
        return messages, offered(await self.tools.specs(), lookup)

    def _opening(self, user: str | tuple[ContentPart, ...]) -> tuple[list[ChatMessage], Intent | None]:
        """The first step's messages for `user`, and the reading of the request (None for audio)."""
        messages = [ChatMessage("system", self.system_prompt), *self._history, ChatMessage("user", user)]
        # audio to an audio model has no words to read; an answer to the robot's own question
        # ("Which room?" - "The bedroom.") asks for what the question offered
        answering = bool(self._history) and self._history[-1].text.rstrip().endswith("?")
        intent = read_request(user, answering=answering) if isinstance(user, str) else None
        if intent is not None and len(intent.steps) > 1:  # a compound request: one thing at a time, in order
            messages.append(ChatMessage("user", step_hint(intent.worded_steps[0], intent.lookups[0], first=True)))
        return messages, intent

    async def _run_tool(
        self, request: ToolCallRequested, metrics: TurnMetrics, emit: Emit, intent: Intent | None,
        spec: ToolSpec | None, said: set[str], doubtful: bool = False,
    ) -> tuple[ToolCalled, ToolReturned]:
        tools, voice = await self.tools.specs(), self.tools.voice()
        arguments, refused = checked(intent if self.checks else None, spec, request.arguments, said, voice,
                                     doubtful=doubtful, tools=tools)  # a switch sent the way the words say
        request = dataclasses.replace(request, arguments=arguments)
        called = ToolCalled(request.id, request.name, dict(request.arguments))
        metrics.mark(f"tool_call:{request.name}")
        await emit(called)
        if (refused is not None and request.name in voice and voice[request.name].role in ("stop", "cancel")
                and halts(intent)):
            # the robot's stop or cancel when the words may mean it though nothing new was asked ("Hold it!
            # Stay put!" read as talk, "never mind" during a drive; `halting.halts`): it runs unless the robot
            # is known to stand still ("Wait, don't call anyone." answered "I am standing still.")
            refused = refused if await self._standing_still(voice) else None
        if refused is None and doubtful and self.checks and (asked := confirm_question(voice, request.name,
                                                                                        request.arguments)):
            refused = held(request.name, asked)  # it never reaches the robot unless the person says yes
            self.confirmations.hold(request, asked)
        if refused is not None:  # the user did not ask for this: it never reaches the robot
            outcome = ToolOutcome(json.dumps(refused), True, 0.0, refused)
        elif request.arguments_error is not None:
            body = {"error": "invalid_arguments", "message": request.arguments_error,
                    "hint": "call the tool again with a JSON object of arguments", "details": {}}
            outcome = ToolOutcome(json.dumps(body), True, 0.0, body)
        else:
            async def on_progress(progress: float, total: float | None, message: str | None) -> None:
                await emit(ToolProgressed(request.name, progress, total, message or ""))

            outcome = await self.tools.call(request.name, dict(request.arguments), on_progress)
        metrics.tools_ms += outcome.duration_ms
        metrics.mark(f"tool_result:{request.name}")
        returned = ToolReturned(request.id, request.name, outcome.text, outcome.is_error, outcome.duration_ms,
                                outcome.error, outcome.structured)
        await emit(returned)
        return called, returned

    async def _standing_still(self, voice: Mapping[str, VoiceDecl]) -> bool:
        """The pose snapshot (voice role "pose") says the robot is still; False when it does not say."""
        poses = tools_with_role(voice, "pose")
        return bool(poses) and await PoseMotionProbe(self.tools, poses[0])() is False

    def _remember(self, turn_messages: Sequence[ChatMessage]) -> None:
        """Keep a bounded history that starts at a user message (`turn_rules.bounded_history`)."""
        self._history = turn_rules.bounded_history(turn_messages, self.max_history_messages)
