"""The conversation loop: model → tool calls → results back → model, one turn at a time.

Text the model streams is split into sentences as it arrives and each complete sentence is
handed on at once (`SentenceReady`), so speech can start while the model still generates.
Robot-side tool errors go back to the model as tool results so it can recover (ask the user,
list the places). When no backend answers, the turn ends with the spoken fallback message.
"""

from __future__ import annotations

import json
import logging
import time
from collections.abc import Awaitable, Callable, Collection, Mapping, Sequence
from dataclasses import dataclass

from robovoice.assistant import turn_rules
from robovoice.assistant.events import (
    BackendFailed,
    FirstTokenReceived,
    SentenceReady,
    ToolCalled,
    ToolProgressed,
    ToolReturned,
    TurnEvent,
    TurnFinished,
    TurnStarted,
    notify,
)
from robovoice.assistant.gate import halts, refusal
from robovoice.assistant.intent import Intent, read_request
from robovoice.assistant.lexicon import words
from robovoice.assistant.metrics import TurnMetrics
from robovoice.assistant.motion_probe import PoseMotionProbe
from robovoice.assistant.phrase import found_phrase, phrase_answer
from robovoice.assistant.prompt import GUESSED_HINT, SYSTEM_PROMPT, step_hint
from robovoice.assistant.robot_tools import Toolbox, ToolOutcome
from robovoice.assistant.speech_guard import (
    MODEL_ONLY,
    ModelOnlyText,
    TurnActions,
    figures_in,
    in_first_person,
    invented_figure_in,
    speakable,
)
from robovoice.assistant.turn_rules import asked_left, call_key, done, is_repeat, offered, wordless_reply
from robovoice.audio.sentences import SentenceSplitter
from robovoice.errors import LLMError
from robovoice.llm.base import ChatMessage, ContentPart, Finished, LLMBackend, TextDelta, ToolCallRequested, ToolSpec
from robovoice.llm.failover import FALLBACK_MESSAGE
from robovoice.manifest.voice import VoiceDecl, tools_with_role

log = logging.getLogger(__name__)

Observer = Callable[[TurnEvent], Awaitable[None] | None]
_Emit = Callable[[TurnEvent], Awaitable[None]]


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
    ) -> None:
        if max_steps < 1:
            raise ValueError("max_steps must be at least 1")
        self.backend = backend
        self.tools = tools
        self.system_prompt = system_prompt
        self.max_steps = max_steps
        self.max_history_messages = max_history_messages
        self.fallback_message = fallback_message
        self._observer = observer
        self._history: list[ChatMessage] = []

    def reset(self) -> None:
        """Forget the conversation (a fresh one per evaluation case)."""
        self._history.clear()

    @property
    def history(self) -> Sequence[ChatMessage]:
        return tuple(self._history)

    def _emitter(self, observer: Observer | None) -> _Emit:
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
    ) -> TurnResult:
        """Run one user turn to its spoken reply. `observer` gets this turn's events (after
        the conversation's observer): a voice turn routes its sentences to speech with it."""
        metrics = metrics or TurnMetrics()
        emit = self._emitter(observer)
        await emit(TurnStarted(ChatMessage("user", user).text))
        messages, intent = self._opening(user)
        asked = intent.steps if intent is not None else ()
        lookups = intent.lookups if intent is not None else ()
        worded = 0  # look-ups of a compound request the model answered in words, without a call
        # what a "there" or a "her" can refer to: what the person and the robot said before
        said = {w for m in self._history if m.role in ("user", "assistant") for w in words(m.text)}
        max_steps = max(self.max_steps, len(asked) + 2)
        replies: list[str] = []
        calls: list[ToolCalled] = []
        outcomes: list[ToolReturned] = []
        fell_back = False
        steps = 0
        looked_up: set[str] = set()  # read-only calls (name and arguments) made since the last action
        answer_now = False
        model_only = MODEL_ONLY.copy()  # what is never said: the prompt, hints, this turn's tool hints
        for tool in (tools := await self.tools.specs()):  # and their descriptions (a small model reads them back)
            model_only.add(tool.description, short_copies=False)
        read_only = {s.name for s in tools if s.read_only}
        retried = lookup_only = False  # asked again after a guessed figure / this step offers only look-ups
        fitting: list[str] = []  # after a call that did not fit the request: the tools that do

        def next_step() -> ChatMessage:  # the hint for the next thing asked (docs/llm.md)
            due = done(outcomes, worded)
            return ChatMessage("user", step_hint(asked[due], lookups[due], first=False))

        for step in range(max_steps):
            steps = step + 1
            # On the last step the model gets no tools, so the turn ends with words, not a call.
            offer = step < max_steps - 1 and not answer_now
            specs: list[ToolSpec] = await self.tools.specs() if offer else []
            lookup = asked_left(asked, outcomes, worded) and lookups[done(outcomes, worded)]
            specs = offered(specs, lookup or lookup_only, fitting)
            lookup_only, fitting = False, []
            try:
                text, requested, guessed = await self._model_step(messages, specs, metrics, emit, model_only,
                                                                  TurnActions(calls, outcomes, read_only))
            except LLMError as exc:
                log.warning("no LLM backend answered: %s", exc)
                fell_back = True
                await emit(BackendFailed(str(exc), self.fallback_message))
                await self._say(self.fallback_message, metrics, emit)
                replies.append(self.fallback_message)
                break
            if requested and not specs:  # a call written as text on the no-tools step: not run
                log.info("the model called %s on a step that offers no tools; not run", [r.name for r in requested])
                requested = []
            by_name = {spec.name: spec for spec in specs}
            if lookup and any(r.name not in by_name for r in requested):
                log.info("the model called %s on a look-up step; not run", [r.name for r in requested])
                requested = [r for r in requested if r.name in by_name]
            if requested and all(is_repeat(r, by_name, looked_up) for r in requested):
                # the same look-up again: its result is already in front of the model (a small
                # model on a strict call grammar repeats it until tools are withdrawn). The
                # repeat is not run; the model answers now, or does the next thing asked.
                log.info("the model repeated %s; not run", [r.name for r in requested])
                requested = []
                if not text:
                    answer_now = not asked_left(asked, outcomes, worded)
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
            if not requested and lookup and text and step < max_steps - 2:
                # the look-up answered in words: the next thing asked is still to do
                worded += 1
                if asked_left(asked, outcomes, worded):
                    messages.append(next_step())
                    continue
            if not requested:
                break
            ran: list[tuple[ToolCalled, ToolReturned]] = []
            for request in requested:
                spec = by_name.get(request.name)
                called, returned = await self._run_tool(request, metrics, emit, intent, spec, said)
                ran.append((called, returned))
                messages.append(ChatMessage("tool", returned.text, tool_call_id=request.id, name=request.name))
                if spec is not None and spec.read_only:
                    looked_up.add(call_key(request))
                else:
                    looked_up.clear()  # an action may change what a look-up returns
            calls.extend(c for c, _ in ran)
            outcomes.extend(r for _, r in ran)
            fitting = turn_rules.refused_for_fit([r for _, r in ran])
            for _, r in ran:  # a tool error's hint is for the model: never read out
                hint = r.result.get("hint") if r.is_error and r.result is not None else None
                if isinstance(hint, str):
                    model_only.add(hint)
            more = asked_left(asked, outcomes, worded) and step < max_steps - 2
            # the tool's own phrase answers this step when it fills and nothing was asked it
            # does not answer: no model step just to word it (assistant/phrase.py)
            # (a look-up's phrase too when more is asked: the turn goes on, and the person hears
            # what was found before the robot moves on)
            phrase = phrase_answer(intent, self.tools.voice(), ran, {s.name for s in specs if s.read_only},
                                   continuing=more)
            if phrase is not None:
                await self._say(phrase, metrics, emit)
                replies.append(phrase)
                messages.append(ChatMessage("assistant", phrase))
                if not more:
                    metrics.mark("phrase_answer")
                    break
            if more:
                # a compound request: the small model tends to answer after the first call, so it
                # is told which of the things the user asked comes next
                messages.append(next_step())
        if not fell_back and not any(r.strip() for r in replies):  # the person always hears an answer
            words_ = found_phrase(self.tools.voice(), calls, outcomes, read_only) or wordless_reply(outcomes, read_only)
            log.info("the model ended the turn without words; said %r", words_)
            await self._say(words_, metrics, emit)
            replies.append(words_)
            messages.append(ChatMessage("assistant", words_))
        reply = " ".join(r.strip() for r in replies if r.strip())
        if not fell_back:
            self._remember(messages[1:])
        metrics.mark("finished")
        await emit(TurnFinished(reply, tuple(calls), steps))
        return TurnResult(reply, tuple(calls), tuple(outcomes), metrics, fell_back)

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
            messages.append(ChatMessage("user", step_hint(intent.steps[0], intent.lookups[0], first=True)))
        return messages, intent

    async def _model_step(
        self, messages: list[ChatMessage], specs: list[ToolSpec], metrics: TurnMetrics, emit: _Emit,
        model_only: ModelOnlyText, actions: TurnActions,
    ) -> tuple[str, list[ToolCallRequested], bool]:
        """One model step, its sentences said as they come: what it said, the calls it asked for, and
        whether a sentence was held back for a figure nobody gave it. `actions`: what the turn's
        calls did so far, so a sentence claiming an action they did not do is not said."""
        splitter = SentenceSplitter()
        known = figures_in(m.text for m in messages)  # what a figure the model says may come from
        text: list[str] = []
        requested: list[ToolCallRequested] = []
        guessed = False
        started = time.perf_counter()
        first = True
        waited = 0.0  # time spent waiting on the model, excluding our own handling of its output
        mark = started
        async for event in self.backend.stream(messages, specs):
            now = time.perf_counter()
            waited += now - mark
            if first:
                first = False
                metrics.mark("first_token")
                await emit(FirstTokenReceived(self.backend.name))
            match event:
                case TextDelta(delta):
                    for sentence in splitter.feed(delta):
                        guessed |= await self._say_speakable(sentence, text, metrics, emit, model_only, known,
                                                             actions)
                case ToolCallRequested():
                    requested.append(event)
                case Finished():
                    pass
            mark = time.perf_counter()
        metrics.model_ms += waited * 1000.0
        rest = splitter.flush()
        if rest:
            guessed |= await self._say_speakable(rest, text, metrics, emit, model_only, known, actions)
        for i, request in enumerate(requested):
            if not request.id:  # some servers omit ids; the history needs them to pair results
                requested[i] = ToolCallRequested(f"call_{len(messages)}_{i}", request.name, request.arguments,
                                                 request.raw_arguments, request.arguments_error)
        return " ".join(text).strip(), requested, guessed

    async def _say_speakable(
        self, sentence: str, said: list[str], metrics: TurnMetrics, emit: _Emit, model_only: ModelOnlyText,
        known: Collection[float], actions: TurnActions,
    ) -> bool:
        """Say a sentence of the model's (in the first person) and keep it in `said`, unless it reads out words meant
        for the model only or tool-call syntax (`speech_guard`), gives a measured figure found
        nowhere in the conversation (`known`), or claims an action the turn did not do
        (`actions`): then it is neither said nor kept, and a turn left with nothing
        said ends with its look-ups' phrases (`found_phrase`) or `wordless_reply`, not in silence.
        True when it was held back for such a figure."""
        spoken = speakable(sentence, model_only)
        if spoken is None:
            log.warning("not saying %r: tool-call syntax or the model's instructions", sentence)
            return False
        spoken = in_first_person(spoken)
        figure = invented_figure_in(spoken, known)
        if figure is not None:
            log.warning("not saying %r: %r is a figure nobody gave the model", sentence, figure)
            return True
        claim = actions.false_claim(spoken)
        if claim is not None:
            log.warning("not saying %r: it claims an action (%r) this turn did not do", sentence, claim)
            return False
        said.append(spoken.strip())
        await self._say(spoken, metrics, emit)
        return False

    @staticmethod
    async def _say(sentence: str, metrics: TurnMetrics, emit: _Emit) -> None:
        metrics.mark("first_sentence")
        await emit(SentenceReady(sentence))

    async def _run_tool(
        self, request: ToolCallRequested, metrics: TurnMetrics, emit: _Emit, intent: Intent | None,
        spec: ToolSpec | None, said: set[str],
    ) -> tuple[ToolCalled, ToolReturned]:
        called = ToolCalled(request.id, request.name, dict(request.arguments))
        metrics.mark(f"tool_call:{request.name}")
        await emit(called)
        voice = self.tools.voice()
        refused = refusal(intent, spec, request.arguments, said, voice)
        if (refused is not None and request.name in voice and voice[request.name].role in ("stop", "cancel")
                and halts(intent)):
            # the robot's stop or cancel when the words asked for nothing new but may mean it
            # ("Hold it! Stay put!" read as talk, "never mind" during a drive; `gate.halts`): it
            # runs unless the robot is known to stand still, where it would do nothing the person
            # asked for ("Wait, don't call anyone." answered "I am standing still.")
            refused = refused if await self._standing_still(voice) else None
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
        """The robot's pose snapshot (voice role "pose") says it is not moving; False when
        there is none, it fails, does not answer in time or does not say."""
        poses = tools_with_role(voice, "pose")
        return bool(poses) and await PoseMotionProbe(self.tools, poses[0])() is False

    def _remember(self, turn_messages: list[ChatMessage]) -> None:
        """Keep a bounded history that starts at a user message (tool results stay paired).

        When it outgrows `max_history_messages` it is cut to about half, not by one turn: a
        model server (or the embedded model) that reuses the evaluated prompt prefix then only
        re-evaluates the conversation once every few turns, instead of on every turn once the
        window is full (measured in the demo: the first token of a late turn went from 6 s to
        the usual 1.5-2 s)."""
        history = [m if m.role != "user" else ChatMessage("user", m.text) for m in turn_messages]  # drop audio
        if len(history) > self.max_history_messages:
            history = history[-max(1, self.max_history_messages // 2):]
        while history and history[0].role != "user":
            history.pop(0)
        self._history = history
