"""Real servers' quirks, each produced on the HTTP wire by the fake server (`Quirks`) and read
by `OpenAICompatBackend`: each becomes a proper tool call, a proper answer or a structured error."""

from __future__ import annotations

import time
from collections.abc import AsyncIterator, Sequence

import pytest

from robovoice.errors import LLMError
from robovoice.llm.base import (
    ChatMessage,
    DeadlineExceededError,
    Deadlines,
    Finished,
    LLMEvent,
    LLMHTTPError,
    TextDelta,
    ToolCallRequested,
    ToolSpec,
)
from robovoice.llm.failover import FailoverBackend
from robovoice.llm.fake_server import (
    FakeOpenAIServer,
    Pacing,
    Quirks,
    ScriptedCall,
    ScriptedReply,
    TextCallStyle,
    TextReply,
    ToolCallReply,
)
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.llm.retry_after import RetryAfterError

from .conftest import NAVIGATE_TO, SET_PROJECTOR, STOP_ROBOT

BATTERY = ToolSpec("get_battery_state", "The battery level and whether it is charging.")
TOOLS = [NAVIGATE_TO, STOP_ROBOT, SET_PROJECTOR, BATTERY]
CALM = Deadlines(connect_s=3.0, first_token_s=10.0, idle_s=10.0, total_s=30.0)  # a loaded machine is slow
USER = [ChatMessage("system", "You are a home robot."), ChatMessage("user", "Go to the kitchen")]
DRIVE = ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),), arg_chunk_chars=3)
SYNTAX = ("<tool_call", "</tool_call", "functions.", '"name"', '"arguments"', "[TOOL_CALLS]")


async def collect(events: AsyncIterator[LLMEvent]) -> list[LLMEvent]:
    return [event async for event in events]


async def run(quirks: Quirks, *replies: ScriptedReply, deadlines: Deadlines = CALM,
              tools: Sequence[ToolSpec] = TOOLS, stream: bool = True) -> tuple[list[LLMEvent], FakeOpenAIServer]:
    """One turn against a server with `quirks`; the events and the server (for its requests)."""
    async with FakeOpenAIServer(replies, quirks=quirks) as srv:
        llm = OpenAICompatBackend(srv.base_url, srv.model, deadlines=deadlines,
                                  extra_body={} if stream else {"stream": False})
        try:
            return await collect(llm.stream(USER, tools)), srv
        finally:
            await llm.aclose()


def text_of(events: list[LLMEvent]) -> str:
    return "".join(e.text for e in events if isinstance(e, TextDelta))


def calls_of(events: list[LLMEvent]) -> list[tuple[str, dict[str, object]]]:
    return [(e.name, e.arguments) for e in events if isinstance(e, ToolCallRequested)]


def finish_of(events: list[LLMEvent]) -> Finished:
    last = events[-1]
    assert isinstance(last, Finished), events
    return last


def assert_no_syntax_in_text(events: list[LLMEvent]) -> None:
    text = text_of(events)
    assert not any(s in text for s in SYNTAX), text


# --- no finish_reason ----------------------------------------------------------------------------


async def test_no_finish_reason_on_a_text_answer_is_a_stop() -> None:
    events, _ = await run(Quirks(no_finish_reason=True), TextReply("The kitchen is on the left."))
    assert text_of(events) == "The kitchen is on the left."
    assert finish_of(events).reason == "stop"


async def test_no_finish_reason_on_tool_calls_is_tool_calls() -> None:
    events, _ = await run(Quirks(no_finish_reason=True), DRIVE)
    assert calls_of(events) == [("navigate_to", {"target": "kitchen"})]
    assert finish_of(events).reason == "tool_calls"


async def test_a_stream_cut_without_done_or_finish_reason_is_still_an_error() -> None:
    cut = TextReply("I have arrived in the", chunk_chars=4, pacing=Pacing(cut_after_chunks=2))
    with pytest.raises(LLMError, match=r"without a finish reason or \[DONE\]"):
        await run(Quirks(no_finish_reason=True), cut)


# --- tool calls written as text in content ------------------------------------------------------


async def test_llama_cpp_bare_functions_head_is_a_call_not_speech() -> None:
    """What llama-cpp-python's chatml-function-calling sent as a plain reply in the field (its
    message path is constrained by the call grammar): content ``functions.get_battery_state:``."""
    reply = ToolCallReply((ScriptedCall("get_battery_state", ""),))
    events, _ = await run(Quirks(no_finish_reason=True, tool_calls_as="functions"), reply)
    assert text_of(events) == ""
    assert calls_of(events) == [("get_battery_state", {})]
    assert finish_of(events).reason == "tool_calls"


@pytest.mark.parametrize("style", ["hermes", "functions", "json", "mistral"])
@pytest.mark.parametrize("chunk", [1, 3, 7])
async def test_a_call_written_as_text_becomes_a_tool_call(style: TextCallStyle, chunk: int) -> None:
    reply = ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),), arg_chunk_chars=chunk)
    events, _ = await run(Quirks(tool_calls_as=style), reply)
    assert calls_of(events) == [("navigate_to", {"target": "kitchen"})]
    assert text_of(events) == ""
    assert finish_of(events).reason == "tool_calls"  # the server said "stop": it did not know


@pytest.mark.parametrize("style", ["hermes", "functions", "mistral"])
async def test_several_calls_written_as_text_keep_their_order(style: TextCallStyle) -> None:
    reply = ToolCallReply((ScriptedCall("stop_robot"), ScriptedCall("set_projector_power", {"on": True})))
    events, _ = await run(Quirks(tool_calls_as=style), reply)
    assert calls_of(events) == [("stop_robot", {}), ("set_projector_power", {"on": True})]
    ids = [e.id for e in events if isinstance(e, ToolCallRequested)]
    assert len(set(ids)) == 2 and all(ids)


async def test_hermes_text_before_the_call_is_spoken_and_the_call_is_not() -> None:
    reply = ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),), text="On my way to the kitchen.")
    events, _ = await run(Quirks(tool_calls_as="hermes"), reply)
    assert text_of(events).strip() == "On my way to the kitchen."
    assert calls_of(events) == [("navigate_to", {"target": "kitchen"})]
    assert_no_syntax_in_text(events)


async def test_hermes_call_with_broken_json_goes_back_to_the_model_not_to_the_user() -> None:
    reply = ToolCallReply((ScriptedCall("navigate_to", '{"target": "kitch'),))
    events, _ = await run(Quirks(tool_calls_as="hermes"), reply)
    assert_no_syntax_in_text(events)
    (call,) = [e for e in events if isinstance(e, ToolCallRequested)]
    assert call.name == "navigate_to" and call.arguments == {} and call.arguments_error is not None


async def test_an_unknown_name_in_tool_call_tags_is_still_a_call() -> None:
    """The loop answers it with an unknown-tool error to the model; it is never spoken."""
    events, _ = await run(Quirks(tool_calls_as="hermes"), ToolCallReply((ScriptedCall("dance", {"style": "waltz"}),)))
    assert calls_of(events) == [("dance", {"style": "waltz"})]
    assert_no_syntax_in_text(events)


async def test_a_bare_json_object_naming_no_offered_tool_is_not_a_call() -> None:
    """A bare JSON answer is ambiguous: only an offered tool's name makes it a call (the speech
    guard keeps such text from being spoken: tests/voice/test_speech_guard.py)."""
    events, _ = await run(Quirks(tool_calls_as="json"), ToolCallReply((ScriptedCall("dance", {}),)))
    assert calls_of(events) == []
    assert text_of(events) == '{"name": "dance", "arguments": {}}'


async def test_text_that_merely_mentions_functions_is_spoken_whole() -> None:
    text = "I have several functions.\nfunctions. That is a plural noun. {Braces} too."
    events, _ = await run(Quirks(tool_calls_as="functions"), TextReply(text, chunk_chars=2))
    assert text_of(events) == text and calls_of(events) == []
    assert finish_of(events).reason == "stop"


async def test_plain_text_is_not_held_back_to_the_end() -> None:
    """Only what could start a call is held: the first words of an answer stream at once, not
    after the server's 2 s stall (measured as the gap between deltas, robust to a loaded machine)."""
    reply = TextReply("Hello there, I am the robot.", chunk_chars=4, pacing=Pacing(stall_after_chunks=3, stall_s=2.0))
    async with FakeOpenAIServer([reply], quirks=Quirks(tool_calls_as="hermes")) as srv:
        llm = OpenAICompatBackend(srv.base_url, srv.model, deadlines=CALM)
        arrivals: list[tuple[float, LLMEvent]] = []
        async for event in llm.stream(USER, TOOLS):
            arrivals.append((time.monotonic(), event))
        await llm.aclose()
    deltas = [(t, e.text) for t, e in arrivals if isinstance(e, TextDelta)]
    assert deltas[0][1] == "Hell"
    after_stall = next(t for t, text in deltas if "I a" in text)
    assert after_stall - deltas[0][0] >= 1.5  # the first words came before the stall, not with the rest
    assert "".join(text for _, text in deltas) == "Hello there, I am the robot."


# --- a server that cannot stream tool calls (llama-cpp-python 0.3.36, chatml-function-calling) -----


async def test_an_empty_stream_for_a_tool_call_is_asked_again_without_streaming() -> None:
    quirks = Quirks(no_streamed_tool_calls=True, keep_alives=True)
    async with FakeOpenAIServer([DRIVE, TextReply("I'm in the kitchen."), TextReply("Hello.")], quirks=quirks) as srv:
        llm = OpenAICompatBackend(srv.base_url, srv.model, deadlines=CALM)
        first = await collect(llm.stream(USER, TOOLS))
        second = await collect(llm.stream(USER, TOOLS))
        third = await collect(llm.stream(USER, []))
        await llm.aclose()
    assert calls_of(first) == [("navigate_to", {"target": "kitchen"})] and finish_of(first).reason == "tool_calls"
    assert not llm.streams_tool_calls  # remembered: the next step with tools is not streamed
    assert text_of(second) == "I'm in the kitchen." and text_of(third) == "Hello."
    bodies = [r.body for r in srv.requests]
    assert [b["stream"] for b in bodies] == [True, False, False, True]  # without tools it still streams
    assert "stream_options" not in bodies[1] and bodies[1]["messages"] == bodies[0]["messages"]
    peers = [r.peer for r in srv.requests]
    assert peers[1] != peers[0]  # asked again on a fresh connection (llama-cpp-python drops the old one) ...
    assert peers[3] == peers[2] == peers[1]  # ... which is then kept alive as usual


async def test_an_empty_stream_without_tools_is_a_clear_error() -> None:
    with pytest.raises(LLMError, match=r"ended before any answer \(no data, no \[DONE\]\)"):
        await run(Quirks(no_streamed_tool_calls=True), DRIVE, tools=[])


# --- arguments as an object, missing usage, unknown fields, keep-alives -------------------------


@pytest.mark.parametrize("stream", [True, False], ids=["streamed", "not-streamed"])
async def test_arguments_sent_as_an_object(stream: bool) -> None:
    reply = ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),
                           ScriptedCall("set_projector_power", {"on": False})))
    events, srv = await run(Quirks(arguments_as_object=True), reply, stream=stream)
    assert srv.requests[0].body["stream"] is stream
    assert calls_of(events) == [("navigate_to", {"target": "kitchen"}), ("set_projector_power", {"on": False})]
    assert all(e.arguments_error is None for e in events if isinstance(e, ToolCallRequested))


@pytest.mark.parametrize("stream", [True, False], ids=["streamed", "not-streamed"])
async def test_no_usage(stream: bool) -> None:
    events, srv = await run(Quirks(no_usage=True), TextReply("Hello."), stream=stream)
    assert text_of(events) == "Hello." and finish_of(events) == Finished("stop", None)
    if stream:
        assert srv.requests[0].body["stream_options"] == {"include_usage": True}  # asked, not given


@pytest.mark.parametrize("stream", [True, False], ids=["streamed", "not-streamed"])
async def test_unknown_fields_everywhere_are_ignored(stream: bool) -> None:
    events, _ = await run(Quirks(unknown_fields=True), TextReply("Hello."), DRIVE, stream=stream)
    assert text_of(events) == "Hello." and finish_of(events).reason == "stop"
    events, _ = await run(Quirks(unknown_fields=True, no_finish_reason=True), DRIVE, stream=stream)
    assert calls_of(events) == [("navigate_to", {"target": "kitchen"})]


async def test_sse_comments_and_keep_alives_between_chunks() -> None:
    reply = TextReply("Fine, thank you.", chunk_chars=3, pacing=Pacing(chunk_interval_s=0.25))
    events, _ = await run(Quirks(keep_alives=True), reply, DRIVE)
    assert text_of(events) == "Fine, thank you." and finish_of(events).reason == "stop"


async def test_keep_alives_are_not_a_first_token() -> None:
    """A server that pings every 0.1 s while it reads the prompt still misses its first-token deadline."""
    slow = TextReply("Hello.", pacing=Pacing(first_token_delay_s=3.0))
    deadlines = Deadlines(connect_s=2.0, first_token_s=0.8, idle_s=5.0, total_s=20.0)
    with pytest.raises(DeadlineExceededError) as info:  # not the text 3 s later: the pings did not count
        await run(Quirks(keep_alives=True), slow, deadlines=deadlines)
    assert info.value.deadline == "first_token"


# --- 429 / 503 with Retry-After -------------------------------------------------------------------


@pytest.mark.parametrize("status", [429, 503])
async def test_busy_with_a_short_retry_after_is_retried_once(status: int) -> None:
    quirks = Quirks(busy_status=status, busy_retry_after="0.3")
    start = time.monotonic()
    events, srv = await run(quirks, TextReply("Hello."))
    assert time.monotonic() - start >= 0.3  # it waited as asked
    assert text_of(events) == "Hello." and len(srv.requests) == 2


async def test_busy_with_an_http_date_retry_after() -> None:
    from email.utils import formatdate

    events, srv = await run(Quirks(busy_status=503, busy_retry_after=formatdate(time.time() - 5, usegmt=True)),
                            TextReply("Hello."))
    assert text_of(events) == "Hello." and len(srv.requests) == 2  # a date already past: retried at once


async def test_busy_longer_than_the_first_token_deadline_is_a_structured_error_at_once() -> None:
    start = time.monotonic()
    with pytest.raises(RetryAfterError) as info:
        await run(Quirks(busy_status=429, busy_retry_after="30"), TextReply("Hello."))
    assert time.monotonic() - start < 10.0  # not 30 s: failover can move on
    err = info.value
    assert isinstance(err, LLMHTTPError) and err.status_code == 429 and err.retry_after == 30.0
    assert err.server_message == "server busy, try again later" and "retry after 30 s" in str(err)


async def test_busy_twice_is_retried_only_once() -> None:
    with pytest.raises(RetryAfterError) as info:
        await run(Quirks(busy_status=503, busy_retry_after="0.1", busy_requests=2), TextReply("Hello."))
    assert info.value.retry_after == pytest.approx(0.1)


async def test_busy_without_retry_after_is_a_plain_http_error() -> None:
    with pytest.raises(LLMHTTPError) as info:
        await run(Quirks(busy_status=503, busy_retry_after=None), TextReply("Hello."))
    assert not isinstance(info.value, RetryAfterError) and info.value.status_code == 503


async def test_a_busy_backend_that_asks_for_long_is_failed_over_at_once() -> None:
    async with (FakeOpenAIServer([TextReply("Busy one.")], quirks=Quirks(busy_status=429, busy_retry_after="60"))
                as busy, FakeOpenAIServer([TextReply("I am the spare.")], model="spare") as spare):
        chain = FailoverBackend([OpenAICompatBackend(busy.base_url, busy.model, deadlines=CALM),
                                 OpenAICompatBackend(spare.base_url, spare.model, deadlines=CALM)])
        start = time.monotonic()
        events = await collect(chain.stream(USER, TOOLS))
        took = time.monotonic() - start
        await chain.aclose()
    assert text_of(events) == "I am the spare." and took < 15.0  # not the 60 s the busy one asked for
    assert len(busy.requests) == 1
