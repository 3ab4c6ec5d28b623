"""The embedded model for real: Qwen2.5-Coder-1.5B through llama-cpp-python (integration).

Assertions are on tool calls, token counts and a 20x difference in evaluated
tokens, never on absolute times (the machine is shared).
"""

from __future__ import annotations

from collections.abc import AsyncIterator, Sequence

import pytest
import pytest_asyncio

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.prompt import SYSTEM_PROMPT
from robovoice.config import RobotConfig
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
from robovoice.llm.local import LocalLlamaBackend
from robovoice.llm.local_head import TOOL_BIAS, HeadDecision

from .local_kit import PATIENT, SYSTEM

pytestmark = [
    pytest.mark.integration,
    pytest.mark.asyncio(loop_scope="module"),
    pytest.mark.usefixtures("local_model_installed"),  # tests/conftest.py: fails, never skips
]


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def local() -> AsyncIterator[LocalLlamaBackend]:
    # TOOL_BIAS is calibrated for the assistant's own prompt and the sim robot's tools; the
    # mechanics tests here use a one-line prompt and three tools, so they run untilted (with
    # TOOL_BIAS, "What is your name?" under SYSTEM becomes a call: its margin is about -1).
    backend = LocalLlamaBackend(n_threads=2, deadlines=PATIENT, tool_bias=0.0)
    await backend.load()
    yield backend
    await backend.aclose()


@pytest_asyncio.fixture(loop_scope="module")
async def calibrated(local: LocalLlamaBackend) -> AsyncIterator[LocalLlamaBackend]:
    """The shared model with the default ``tool_bias``, as the assistant runs it."""
    local.tool_bias = TOOL_BIAS
    try:
        yield local
    finally:
        local.tool_bias = 0.0


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
    assert local.last_turn.head_margin is not None and local.last_turn.head_margin > 0


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


async def test_a_step_offering_fewer_tools_keeps_the_evaluated_prefix(
    local: LocalLlamaBackend, tools: list[ToolSpec]
) -> None:
    # the assistant's loop offers only look-ups on some steps and no tools on its last: the
    # prompt still lists every tool warm_up evaluated, and only the grammar narrows the choice
    await local.reset_cache()
    stats = await local.warm_up(SYSTEM.text, tools)
    events = await turn(local, "Please drive to the kitchen", [t for t in tools if t.name != "navigate_to"])
    assert all(call.name != "navigate_to" for call in calls(events))
    assert local.last_turn.cached_prompt_tokens >= stats.prompt_tokens
    events = await turn(local, "What is your name?", [])
    assert "".join(e.text for e in events if isinstance(e, TextDelta)).strip()
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
    await events.aclose()  # barge-in
    events_after = await turn(local, "Please drive to the kitchen", tools)
    assert [c.name for c in calls(events_after)] == ["navigate_to"]


async def test_tool_bias_moves_the_head_decision_exactly_by_the_margin(
    local: LocalLlamaBackend, tools: list[ToolSpec]
) -> None:
    messages = [SYSTEM, ChatMessage("user", "What is your name?")]

    async def decide(bias: float) -> HeadDecision:
        local.tool_bias = bias
        await local.reset_cache()  # the same evaluation every time: logits are then identical
        return await local.decide_head(messages, tools)

    try:
        plain = await decide(0.0)
        assert plain.head.kind == "message" and plain.margin < 0
        short = await decide(-plain.margin - 0.25)  # not quite enough
        tilted = await decide(-plain.margin + 0.25)  # just enough
    finally:
        local.tool_bias = 0.0
    assert short.head.kind == "message"
    assert tilted.head.kind == "call" and tilted.head.tool is not None
    # The margin is measured before the bias, so it does not move with it.
    assert short.margin == pytest.approx(plain.margin, abs=0.01)
    assert tilted.margin == pytest.approx(plain.margin, abs=0.01)


async def test_tool_bias_leaves_the_answer_after_a_tool_result_alone(
    local: LocalLlamaBackend, tools: list[ToolSpec]
) -> None:
    history = [
        SYSTEM,
        ChatMessage("user", "Please drive to the kitchen"),
        ChatMessage("assistant", "", tool_calls=(ToolCall("c1", "navigate_to", '{"target": "kitchen"}'),)),
        ChatMessage("tool", '{"status": "arrived", "place": "kitchen"}', tool_call_id="c1"),
    ]
    try:
        local.tool_bias = 50.0  # would force a call on any user message
        greeting = await local.decide_head([SYSTEM, ChatMessage("user", "Hello!")], tools)
        after_result = await local.decide_head(history, tools)
    finally:
        local.tool_bias = 0.0
    assert greeting.head.kind == "call"
    assert after_result.head.kind == "message" and after_result.margin < 0


async def test_the_assistant_gets_the_calibrated_bias_by_default() -> None:
    backend = LocalLlamaBackend()  # not loaded: construction is cheap
    try:
        assert backend.tool_bias == TOOL_BIAS > 0
    finally:
        await backend.aclose()


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def sim_tools() -> list[ToolSpec]:
    async with connect_robot(RobotConfig(address="sim://")) as link:
        return await link.tools.specs()


@pytest.mark.parametrize(
    ("text", "tool"),
    [
        ("How much battery do you have left?", "get_battery_state"),  # answered from the description at bias 0
        ("What's your battery level?", "get_battery_state"),
        ("Where are you right now?", "get_robot_pose"),
        ("What is your name?", None),
        ("How are you today?", None),
        ("Hello!", None),
    ],
)
async def test_the_default_tool_bias_asks_the_robot_and_leaves_small_talk_alone(
    calibrated: LocalLlamaBackend, sim_tools: list[ToolSpec], text: str, tool: str | None
) -> None:
    """The assistant's real prompt and the sim robot's tools, as in the text evaluation."""
    assert calibrated.tool_bias == TOOL_BIAS > 0
    messages = [ChatMessage("system", SYSTEM_PROMPT), ChatMessage("user", text)]
    decision = await calibrated.decide_head(messages, sim_tools)
    assert (decision.head.tool.name if decision.head.tool else None) == tool, decision.margin
    if tool is None:  # small talk stays clear of the threshold, not just under it
        assert decision.margin + TOOL_BIAS < -0.5


async def test_a_battery_question_streams_a_battery_call(
    calibrated: LocalLlamaBackend, sim_tools: list[ToolSpec]
) -> None:
    messages = [ChatMessage("system", SYSTEM_PROMPT), ChatMessage("user", "How much battery do you have left?")]
    events = [e async for e in calibrated.stream(messages, sim_tools)]
    assert [c.name for c in calls(events)] == ["get_battery_state"]
    assert not any(isinstance(e, TextDelta) for e in events)
    assert calibrated.last_turn.head_margin is not None
