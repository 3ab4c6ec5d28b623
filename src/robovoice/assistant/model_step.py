"""One model step of a turn: the model's stream read as it comes, each complete sentence said
at once (`SentenceReady`) unless the speech guard holds it back, the tool calls collected."""

from __future__ import annotations

import logging
import time
from collections.abc import Awaitable, Callable, Collection

from robovoice.assistant.events import FirstTokenReceived, SentenceReady, TurnEvent
from robovoice.assistant.metrics import TurnMetrics
from robovoice.assistant.speech_guard import (
    ModelOnlyText,
    TurnActions,
    figures_in,
    in_first_person,
    invented_figure_in,
    speakable,
)
from robovoice.audio.sentences import SentenceSplitter
from robovoice.llm.base import ChatMessage, Finished, LLMBackend, TextDelta, ToolCallRequested, ToolSpec

log = logging.getLogger(__name__)

Emit = Callable[[TurnEvent], Awaitable[None]]


async def model_step(
    backend: LLMBackend, messages: list[ChatMessage], specs: list[ToolSpec], metrics: TurnMetrics, emit: Emit,
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
    async for event in backend.stream(messages, specs):
        now = time.perf_counter()
        waited += now - mark
        if first:
            first = False
            metrics.mark("first_token")
            await emit(FirstTokenReceived(backend.name))
        match event:
            case TextDelta(delta):
                for sentence in splitter.feed(delta):
                    guessed |= await _say_speakable(sentence, text, metrics, emit, model_only, known,
                                                         actions)
            case ToolCallRequested():
                requested.append(event)
            case Finished():
                pass
        mark = time.perf_counter()
    metrics.model_ms += waited * 1000.0
    rest = splitter.flush()
    if rest:
        guessed |= await _say_speakable(rest, text, metrics, emit, model_only, known, actions)
    for i, request in enumerate(requested):
        if not request.id:  # some servers omit ids; the history needs them to pair results
            requested[i] = ToolCallRequested(f"call_{len(messages)}_{i}", request.name, request.arguments,
                                             request.raw_arguments, request.arguments_error)
    return " ".join(text).strip(), requested, guessed

async def _say_speakable(
    sentence: str, said: list[str], metrics: TurnMetrics, emit: Emit, model_only: ModelOnlyText,
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
    await say(spoken, metrics, emit)
    return False

async def say(sentence: str, metrics: TurnMetrics, emit: Emit) -> None:
    metrics.mark("first_sentence")
    await emit(SentenceReady(sentence))
