"""The embedded model for real: Qwen2.5-Coder-1.5B through llama-cpp-python (integration).

Assertions are on tool calls, token counts and a 20x difference in evaluated
tokens, never on absolute times (the machine is shared).
"""

from __future__ import annotations

from collections.abc import AsyncIterator, Sequence

import pytest
import pytest_asyncio

from robovoice.llm.base import (
    ChatMessage,
    DeadlineExceededError,
    Deadlines,
    Finished,
    LLMEvent,
    TextDelta,
    ToolCall,
    ToolCallRequested,
    ToolSpec,
)
from robovoice.llm.local import LocalLlamaBackend, llama_cpp_available
from robovoice.llm.model_store import default_model_ready

pytestmark = [
    pytest.mark.integration,
    pytest.mark.asyncio(loop_scope="module"),
    pytest.mark.skipif(
        not llama_cpp_available(), reason="llama-cpp-python not installed: pip install 'robovoice[llm]'"
    ),
    pytest.mark.skipif(not default_model_ready(), reason="model parts not installed: pip install 'robovoice[model]'"),
]

# Correctness, not speed, is tested here: deadlines for a machine shared with other work.
PATIENT = Deadlines(first_token_s=300, idle_s=60, total_s=600)
SYSTEM = ChatMessage("system", "You are the voice assistant of a home robot. Answer briefly. Use the functions to act.")


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def local() -> AsyncIterator[LocalLlamaBackend]:
    backend = LocalLlamaBackend(n_threads=2, deadlines=PATIENT)
    await backend.load()
    yield backend
    await backend.aclose()


async def turn(backend: LocalLlamaBackend, text: str, tools: Sequence[ToolSpec]) -> list[LLMEvent]:
    return [event async for event in backend.stream([SYSTEM, ChatMessage("user", text)], tools)]


def calls(events: list[LLMEvent]) -> list[ToolCallRequested]:
    return [e for e in events if isinstance(e, ToolCallRequested)]


async def test_drive_to_the_kitchen_is_a_navigate_to_call(local: LocalLlamaBackend, tools: list[ToolSpec]) -> None:
    events = await turn(local, "Please drive to the kitchen", tools)
    [call] = calls(events)
    assert call.name == "navigate_to" and call.arguments["target"].strip().lower() == "kitchen"
    assert call.arguments_error is None
    assert isinstance(events[-1], Finished) and events[-1].reason == "tool_calls"


async def test_what_is_your_name_is_a_streamed_answer(local: LocalLlamaBackend, tools: list[ToolSpec]) -> None:
    events = await turn(local, "What is your name?", tools)
    assert calls(events) == []
    deltas = [e for e in events if isinstance(e, TextDelta)]
    assert len(deltas) >= 2 and "".join(d.text for d in deltas).strip()
    assert isinstance(events[-1], Finished) and events[-1].reason == "stop"


async def test_second_turn_reuses_the_prompt_prefix(local: LocalLlamaBackend, tools: list[ToolSpec]) -> None:
    await local.reset_cache()
    first = await turn(local, "Please drive to the kitchen", tools)
    cold = local.last_turn
    second = await turn(local, "What is your name?", tools)
    warm = local.last_turn
    assert isinstance(first[-1], Finished) and isinstance(second[-1], Finished)
    assert second[-1].usage is not None and second[-1].usage.cached_prompt_tokens == warm.cached_prompt_tokens
    assert cold.cached_prompt_tokens == 0 and cold.prompt_tokens > 200
    assert warm.cached_prompt_tokens >= 0.9 * warm.prompt_tokens
    evaluated = warm.prompt_tokens - warm.cached_prompt_tokens
    assert evaluated * 10 < cold.prompt_tokens, (cold, warm)
    assert warm.prompt_eval_ms < cold.prompt_eval_ms, (cold, warm)


async def test_warm_up_evaluates_the_prefix_once(local: LocalLlamaBackend, tools: list[ToolSpec]) -> None:
    await local.reset_cache()
    stats = await local.warm_up(SYSTEM.text, tools)
    assert stats.prompt_tokens > 200
    await turn(local, "Stop right now!", tools)
    assert local.last_turn.cached_prompt_tokens >= stats.prompt_tokens


async def test_a_tool_result_is_read_and_answered(local: LocalLlamaBackend, tools: list[ToolSpec]) -> None:
    history = [
        SYSTEM,
        ChatMessage("user", "Please drive to the kitchen"),
        ChatMessage("assistant", "", tool_calls=(ToolCall("c1", "navigate_to", '{"target": "kitchen"}'),)),
        ChatMessage("tool", '{"status": "arrived", "place": "kitchen"}', tool_call_id="c1"),
    ]
    events = [e async for e in local.stream(history, tools)]
    text = "".join(e.text for e in events if isinstance(e, TextDelta)).lower()
    assert calls(events) == [] and "kitchen" in text


async def test_abandoned_turns_do_not_break_the_next(local: LocalLlamaBackend, tools: list[ToolSpec]) -> None:
    local.deadlines = Deadlines(first_token_s=0.01, idle_s=10, total_s=60)
    try:
        with pytest.raises(DeadlineExceededError, match="first_token"):
            await turn(local, "Tell me a long story about robots.", [])
    finally:
        local.deadlines = PATIENT
    events = local.stream([SYSTEM, ChatMessage("user", "Tell me a long story about robots.")], [])
    assert isinstance(await anext(events), TextDelta)
    await events.aclose()  # type: ignore[attr-defined]  # barge-in
    events_after = await turn(local, "Please drive to the kitchen", tools)
    assert [c.name for c in calls(events_after)] == ["navigate_to"]
