"""FailoverBackend over real HTTP backends (fake servers), with a hand-driven clock."""

from __future__ import annotations

import time
from collections.abc import AsyncIterator
from contextlib import AsyncExitStack

import pytest

from robovoice.errors import BackendUnavailableError, ConfigError
from robovoice.llm.base import (
    AudioPart,
    ChatMessage,
    DeadlineExceededError,
    Deadlines,
    Finished,
    LLMEvent,
    TextDelta,
    ToolSpec,
)
from robovoice.llm.failover import (
    FALLBACK_MESSAGE,
    AllBackendsFailedError,
    Backoff,
    FailoverBackend,
)
from robovoice.llm.fake_server import ErrorReply, FakeOpenAIServer, Pacing, TextReply
from robovoice.llm.openai_compat import OpenAICompatBackend

FAST = Deadlines(connect_s=0.5, first_token_s=0.2, idle_s=0.2, total_s=5.0)
PATIENT = Deadlines(connect_s=5.0, first_token_s=10.0, idle_s=10.0, total_s=20.0)
"""For a healthy server that must answer: a loaded CI machine once took over 0.2 s to its first token."""
USER = [ChatMessage("user", "Hello")]


class Clock:
    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


async def text_of(events: AsyncIterator[LLMEvent]) -> str:
    return "".join([e.text async for e in events if isinstance(e, TextDelta)])


def http(name: str, url: str, *, audio: bool = False, deadlines: Deadlines = FAST) -> OpenAICompatBackend:
    return OpenAICompatBackend(url, "m", name=name, deadlines=deadlines, accepts_audio=audio)


@pytest.fixture
async def stack() -> AsyncIterator[AsyncExitStack]:
    async with AsyncExitStack() as s:
        yield s


async def chain(stack: AsyncExitStack, backends: list[OpenAICompatBackend], clock: Clock) -> FailoverBackend:
    llm = FailoverBackend(backends, backoff=Backoff(initial_s=2, factor=2, max_s=10), clock=clock)
    stack.push_async_callback(llm.aclose)
    return llm


async def test_first_healthy_backend_answers_in_order(stack: AsyncExitStack, tools: list[ToolSpec]) -> None:
    edge = await stack.enter_async_context(FakeOpenAIServer([TextReply("from edge")]))
    cloud = await stack.enter_async_context(FakeOpenAIServer([TextReply("from cloud")]))
    llm = await chain(stack, [http("edge", edge.base_url, deadlines=PATIENT), http("cloud", cloud.base_url)], Clock())
    assert await text_of(llm.stream(USER, tools)) == "from edge"
    assert len(edge.requests) == 1 and cloud.requests == []
    assert all(h.healthy for h in llm.health())


async def test_failed_backend_is_skipped_and_backs_off_then_recovers(
    stack: AsyncExitStack, tools: list[ToolSpec]
) -> None:
    edge = await stack.enter_async_context(
        FakeOpenAIServer(
            [ErrorReply(503, "loading model"), ErrorReply(503, "still loading")], default=TextReply("edge is back")
        )
    )
    cloud = await stack.enter_async_context(FakeOpenAIServer(default=TextReply("from cloud")))
    clock = Clock()
    # both answer in the end: a loaded machine once took over 0.2 s to a first token (CI, 23 Nov)
    backends = [http("edge", edge.base_url, deadlines=PATIENT), http("cloud", cloud.base_url, deadlines=PATIENT)]
    llm = await chain(stack, backends, clock)

    # turn 1: edge fails before any output → cloud answers; edge backs off 2 s
    assert await text_of(llm.stream(USER, tools)) == "from cloud"
    edge_health = llm.health()[0]
    assert not edge_health.healthy and edge_health.consecutive_failures == 1
    assert edge_health.last_error is not None and "loading model" in edge_health.last_error
    assert edge_health.next_retry_at == clock.now + 2

    # turn 2, within the backoff: edge is not even asked
    clock.now += 1.9
    assert await text_of(llm.stream(USER, tools)) == "from cloud"
    assert len(edge.requests) == 1

    # turn 3, backoff over: edge is tried, fails again → backoff doubles to 4 s
    clock.now += 0.2
    assert await text_of(llm.stream(USER, tools)) == "from cloud"
    assert len(edge.requests) == 2
    assert llm.health()[0].next_retry_at == clock.now + 4

    # turn 4, after the longer backoff: edge answers and is healthy again
    clock.now += 4.0
    assert await text_of(llm.stream(USER, tools)) == "edge is back"
    health = llm.health()[0]
    assert health.healthy and health.next_retry_at is None and health.last_success_at == clock.now
    assert len(cloud.requests) == 3


async def test_all_fail_within_a_bounded_time_with_every_reason(
    stack: AsyncExitStack, tools: list[ToolSpec], unused_port: int
) -> None:
    broken = await stack.enter_async_context(FakeOpenAIServer(default=ErrorReply(500, "internal boom")))
    stalled = await stack.enter_async_context(
        FakeOpenAIServer(default=TextReply("never", pacing=Pacing(first_token_delay_s=60)))
    )
    llm = await chain(
        stack,
        [
            http("edge", f"http://127.0.0.1:{unused_port}/v1"),
            http("cloud", broken.base_url),
            http("local", stalled.base_url),
        ],
        Clock(),
    )
    start = time.monotonic()
    with pytest.raises(BackendUnavailableError) as info:
        await text_of(llm.stream(USER, tools))
    assert time.monotonic() - start < 2.0  # 3 backends: refused + HTTP 500 + 0.2 s first-token deadline
    assert isinstance(info.value, AllBackendsFailedError)
    reasons = info.value.reasons
    assert list(reasons) == ["edge", "cloud", "local"]
    assert "cannot reach" in reasons["edge"]
    assert "internal boom" in reasons["cloud"]
    assert "first_token deadline" in reasons["local"]
    assert not any(h.healthy for h in llm.health())
    assert FALLBACK_MESSAGE == "I can't reach my language model right now. Please try again in a moment."


async def test_when_all_back_off_the_soonest_is_tried_anyway(stack: AsyncExitStack, tools: list[ToolSpec]) -> None:
    a = await stack.enter_async_context(FakeOpenAIServer([ErrorReply(500, "a down")], default=TextReply("a ok")))
    b = await stack.enter_async_context(FakeOpenAIServer(default=ErrorReply(500, "b down")))
    clock = Clock()
    llm = await chain(stack, [http("a", a.base_url), http("b", b.base_url)], clock)
    with pytest.raises(AllBackendsFailedError):
        await text_of(llm.stream(USER, tools))
    clock.now += 1  # both still backing off; a is due first (it failed first)
    assert await text_of(llm.stream(USER, tools)) == "a ok"
    assert len(b.requests) == 1


async def test_no_failover_once_a_backend_has_streamed(stack: AsyncExitStack, tools: list[ToolSpec]) -> None:
    reply = TextReply("Hello there", chunk_chars=6, pacing=Pacing(stall_after_chunks=1, stall_s=60))
    edge = await stack.enter_async_context(FakeOpenAIServer([reply]))
    cloud = await stack.enter_async_context(FakeOpenAIServer(default=TextReply("from cloud")))
    llm = await chain(stack, [http("edge", edge.base_url), http("cloud", cloud.base_url)], Clock())
    got: list[LLMEvent] = []
    with pytest.raises(DeadlineExceededError, match="idle"):
        async for event in llm.stream(USER, tools):
            got.append(event)
    assert got == [TextDelta("Hello ")]
    assert cloud.requests == []
    assert not llm.health()[0].healthy


async def test_audio_turns_skip_text_only_backends_without_penalty(
    stack: AsyncExitStack, tools: list[ToolSpec]
) -> None:
    cloud = await stack.enter_async_context(FakeOpenAIServer(default=TextReply("text only")))
    edge = await stack.enter_async_context(FakeOpenAIServer(default=TextReply("heard you")))
    llm = await chain(stack, [http("cloud", cloud.base_url), http("edge", edge.base_url, audio=True)], Clock())
    assert not llm.accepts_audio
    audio_turn = [ChatMessage("user", (AudioPart(b"RIFF....WAVE"),))]
    assert await text_of(llm.stream(audio_turn, tools)) == "heard you"
    assert cloud.requests == [] and llm.health()[0].healthy
    assert await text_of(llm.stream(USER, tools)) == "text only"


async def test_closing_the_stream_early_is_not_a_failure(stack: AsyncExitStack, tools: list[ToolSpec]) -> None:
    edge = await stack.enter_async_context(FakeOpenAIServer(default=TextReply("a long answer", chunk_chars=2)))
    llm = await chain(stack, [http("edge", edge.base_url)], Clock())
    events = llm.stream(USER, tools)
    first = await anext(events)
    assert first == TextDelta("a ")
    await events.aclose()  # barge-in: the caller stops listening
    assert llm.health()[0].healthy
    events = llm.stream(USER, tools)
    assert isinstance([e async for e in events][-1], Finished)


def test_chain_configuration_errors() -> None:
    with pytest.raises(ConfigError):
        FailoverBackend([])
    one = http("same", "http://127.0.0.1:1/v1")
    two = http("same", "http://127.0.0.1:2/v1")
    with pytest.raises(ConfigError, match="unique"):
        FailoverBackend([one, two])


def test_backoff_grows_and_is_capped() -> None:
    backoff = Backoff(initial_s=1, factor=3, max_s=5)
    assert [backoff.delay(n) for n in range(5)] == [0, 1, 3, 5, 5]


class PrefillingBackend(OpenAICompatBackend):
    """A backend that can prefill (as the embedded model can), recording what it was given."""

    def __init__(self, name: str, url: str) -> None:
        super().__init__(url, "m", name=name, deadlines=FAST)
        self.prefilled: list[tuple[list[ChatMessage], bool]] = []

    async def prefill(self, messages: list[ChatMessage], tools: list[ToolSpec], *, decode: bool = True) -> str:
        self.prefilled.append((list(messages), decode))
        return "prefilled"


async def test_prefill_goes_to_the_backend_the_next_turn_tries_first(
    stack: AsyncExitStack, tools: list[ToolSpec]
) -> None:
    from robovoice.voice.speculate import Prefilling

    server = await stack.enter_async_context(FakeOpenAIServer([TextReply("Hi.")]))
    local, remote = PrefillingBackend("local", server.base_url), http("remote", server.base_url)
    stack.push_async_callback(local.aclose)
    clock = Clock()
    llm = await chain(stack, [local, remote], clock)
    assert isinstance(llm, Prefilling)  # what the voice pipeline's speculator checks
    assert await llm.prefill(USER, tools, decode=False) == "prefilled"
    assert local.prefilled == [(USER, False)] and not server.requests  # nothing was sent anywhere
    # with a backend that cannot prefill first in line, nothing is prefilled
    assert await (await chain(stack, [remote, local], clock)).prefill(USER, tools) is None
    assert len(local.prefilled) == 1
