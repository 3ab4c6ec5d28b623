"""Speculative prefill of the embedded model for real (llm/local_speculation.py): the prompt
evaluated, and the tool call decoded, before the turn is asked for.

Assertions are on tokens, events and flags, never on times (the machine is shared).
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import AsyncIterator, Sequence

import pytest
import pytest_asyncio

from robovoice.llm.base import ChatMessage, Finished, LLMEvent, ToolCallRequested, ToolSpec
from robovoice.llm.local import LocalLlamaBackend
from robovoice.llm.local_speculation import evaluate_prompt

from .local_kit import PATIENT, SYSTEM

pytestmark = [
    pytest.mark.integration,
    pytest.mark.asyncio(loop_scope="module"),
    pytest.mark.usefixtures("local_model_installed"),  # tests/conftest.py: fails, never skips
]


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def local() -> AsyncIterator[LocalLlamaBackend]:
    backend = LocalLlamaBackend(n_threads=2, deadlines=PATIENT, tool_bias=0.0)
    await backend.load()
    yield backend
    await backend.aclose()


def asked(text: str) -> list[ChatMessage]:
    return [SYSTEM, ChatMessage("user", text)]


async def run(backend: LocalLlamaBackend, text: str, tools: Sequence[ToolSpec]) -> list[LLMEvent]:
    return [event async for event in backend.stream(asked(text), tools)]


def the_call(events: list[LLMEvent]) -> ToolCallRequested:
    [call] = [e for e in events if isinstance(e, ToolCallRequested)]
    return call


def usage_of(events: list[LLMEvent]) -> tuple[int, int]:
    finished = events[-1]
    assert isinstance(finished, Finished) and finished.usage is not None
    assert finished.usage.cached_prompt_tokens is not None
    return finished.usage.prompt_tokens, finished.usage.cached_prompt_tokens


async def test_the_same_transcript_replays_the_call_decoded_in_the_silence(
    local: LocalLlamaBackend, tools: list[ToolSpec]
) -> None:
    await local.reset_cache()
    plain = the_call(await run(local, "Please drive to the kitchen", tools))
    await local.reset_cache()
    done = await local.prefill(asked("Please drive to the kitchen"), tools)
    assert done is not None and done.decoded_call and not done.stopped and done.evaluated_tokens > 200
    events = await run(local, "Please drive to the kitchen", tools)
    assert local.last_turn.speculative
    call = the_call(events)
    assert (call.name, call.arguments) == (plain.name, plain.arguments) == ("navigate_to", {"target": "kitchen"})
    prompt, cached = usage_of(events)
    assert cached == prompt - 1  # everything but the token llama.cpp re-reads for its logits


async def test_a_changed_transcript_discards_the_call_and_keeps_the_shared_prefix(
    local: LocalLlamaBackend, tools: list[ToolSpec]
) -> None:
    await local.reset_cache()
    done = await local.prefill(asked("Please drive to the kitchen"), tools)
    assert done is not None and done.decoded_call
    events = await run(local, "Please drive to the kitchen and switch the projector on", tools)
    assert not local.last_turn.speculative  # the guessed call was not used
    prompt, cached = usage_of(events)
    evaluated = prompt - cached
    assert 0 < evaluated < 30 and cached > 200  # only the words after "kitchen" and the turn's end
    assert the_call(events).name in {"navigate_to", "set_projector_power"}


async def test_a_message_head_is_prefilled_not_decoded(local: LocalLlamaBackend, tools: list[ToolSpec]) -> None:
    await local.reset_cache()
    done = await local.prefill(asked("What is your name?"), tools)
    assert done is not None and not done.decoded_call and done.evaluated_tokens > 200
    events = await run(local, "What is your name?", tools)
    assert not local.last_turn.speculative and not [e for e in events if isinstance(e, ToolCallRequested)]
    prompt, cached = usage_of(events)
    assert cached == prompt - 1


async def test_a_real_turn_stops_a_prefill_for_another_prompt_and_is_never_held_up_by_one(
    local: LocalLlamaBackend, tools: list[ToolSpec]
) -> None:
    await local.reset_cache()
    guess = asyncio.create_task(local.prefill(asked("Please drive to the kitchen"), tools))
    await asyncio.sleep(0)  # the prefill is on the model thread now
    events = await run(local, "Switch the projector on", tools)
    done = await guess
    assert done is not None and done.stopped and not done.decoded_call
    assert the_call(events).name == "set_projector_power"
    # while a real turn streams, a prefill starts nothing
    stream = local.stream(asked("Switch the projector off"), tools)
    first = await anext(stream)
    assert await local.prefill(asked("Please drive to the kitchen"), tools) is None
    rest = [first, *[e async for e in stream]]
    assert the_call(rest).name == "set_projector_power"


async def test_evaluate_prompt_reuses_the_cached_prefix(local: LocalLlamaBackend) -> None:
    await local.reset_cache()
    llama = local._llama
    text = "<|im_start|>system\nYou are a robot.<|im_end|>\n<|im_start|>user\nGo to the kitchen<|im_end|>\n"
    tokens = llama.tokenize(text.encode(), add_bos=False, special=True)

    def work() -> tuple[int, int, int]:
        first = evaluate_prompt(llama, tokens, threading.Event(), chunk=4)
        again = evaluate_prompt(llama, tokens, threading.Event())
        longer = evaluate_prompt(llama, [*tokens, *tokens[:3]], threading.Event())
        return first, again, longer

    first, again, longer = await asyncio.get_running_loop().run_in_executor(local._executor, work)
    assert (first, again, longer) == (len(tokens), 0, 3)
    stopped = threading.Event()
    stopped.set()
    assert await asyncio.get_running_loop().run_in_executor(
        local._executor, evaluate_prompt, llama, tokens[:5], stopped
    ) == 0
