"""The assistant's tool loop against a real HTTP server speaking vLLM's wire format and the
embedded sim robot behind the real MCP server and SDK client."""

from __future__ import annotations

import itertools
import json
import re
from collections.abc import AsyncIterator

import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.events import BackendFailed, SentenceReady, ToolReturned, TurnEvent
from robovoice.assistant.loop import Assistant
from robovoice.config import RobotConfig
from robovoice.llm.failover import FALLBACK_MESSAGE, Backoff, FailoverBackend
from robovoice.llm.fake_server import (
    ErrorReply,
    FakeOpenAIServer,
    Pacing,
    RecordedRequest,
    ScriptedCall,
    ScriptedReply,
    TextReply,
    ToolCallReply,
)
from robovoice.llm.openai_compat import OpenAICompatBackend

# The robot is opened inside each test, not in a fixture: anyio's cancel scopes must be
# entered and left in the same task, and pytest-asyncio runs fixture teardown in another.
SIM = RobotConfig(address="sim://?speed=50")


_OPENED: list[OpenAICompatBackend] = []


def _backend(server: FakeOpenAIServer) -> OpenAICompatBackend:
    backend = OpenAICompatBackend(server.base_url, server.model)
    _OPENED.append(backend)
    return backend


@pytest.fixture(autouse=True)
async def _close_backends() -> AsyncIterator[None]:
    """Every backend a test opened is closed after it (its HTTP connections with it)."""
    yield
    while _OPENED:
        await _OPENED.pop().aclose()


async def test_tool_loop_drives_the_robot_and_streams_sentences() -> None:
    async with connect_robot(SIM) as robot:
        script: list[ScriptedReply] = [
            ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),), arg_chunk_chars=3),
            TextReply("I'm in the kitchen now. Dr. Weber's number is 3.5, just kidding! Anything else?"),
        ]
        events: list[TurnEvent] = []
        async with FakeOpenAIServer(script) as server:
            assistant = Assistant(_backend(server), robot.tools, observer=events.append)
            # a question beside the drive: the model words the answer (not the drive's phrase)
            result = await assistant.turn("Please go to the kitchen. Is it far?")
            requests = list(server.requests)
        assert [(c.name, c.arguments) for c in result.calls] == [("navigate_to", {"target": "kitchen"})]
        assert robot.sim is not None and robot.sim.state.nearest_place == "kitchen"
        assert not result.outcomes[0].is_error and json.loads(result.outcomes[0].text)["arrived"] == "kitchen"
        sentences = [e.text for e in events if isinstance(e, SentenceReady)]
        assert sentences == ["I'm in the kitchen now.", "Dr. Weber's number is 3.5, just kidding!",
                             "Anything else?"]
        # The model got every sim tool, and the tool result went back paired with its call id.
        assert "navigate_to" in requests[0].tool_names and len(requests[0].tool_names) == 12
        tool_message = requests[1].messages[-2]  # then "Now do the next thing I asked: Is it far."
        assert tool_message["role"] == "tool" and "kitchen" in tool_message["content"]
        assert tool_message["tool_call_id"] == requests[1].messages[-3]["tool_calls"][0]["id"]
        marks = result.metrics.as_dict()
        assert marks["first_token"] <= marks["first_sentence"] <= marks["finished"]
        assert "tool_call:navigate_to" in marks and marks["tools_ms"] > 0


async def test_structured_tool_error_goes_back_and_the_model_recovers() -> None:
    async with connect_robot(SIM) as robot:
        script: list[ScriptedReply] = [
            ToolCallReply((ScriptedCall("navigate_to", {"target": "garage"}),)),
            ToolCallReply((ScriptedCall("get_navigation_targets", {}),)),
            TextReply("I don't know a garage. I can go to the kitchen, the bedroom or the hallway. Which one?"),
        ]
        events: list[TurnEvent] = []
        async with FakeOpenAIServer(script) as server:
            result = await Assistant(_backend(server), robot.tools, observer=events.append).turn("Drive to the garage")
            second = list(server.requests)[1]
        error = next(e for e in events if isinstance(e, ToolReturned) and e.name == "navigate_to")
        assert error.is_error
        body = json.loads(error.text)
        assert body["error"] == "unknown_target" and "kitchen" in body["details"]["known_places"]
        assert "name the known places" in body["hint"]
        assert "unknown_target" in second.messages[-1]["content"]  # the model saw the structured error
        assert [c.name for c in result.calls] == ["navigate_to", "get_navigation_targets"]
        assert result.reply.endswith("Which one?")


async def test_bad_arguments_become_a_tool_error_not_a_call() -> None:
    async with connect_robot(SIM) as robot:
        script: list[ScriptedReply] = [ToolCallReply((ScriptedCall("set_projector_power", '{"on": "yes please"}'),)),
                  ToolCallReply((ScriptedCall("set_projector_power", "{not json"),)),
                  TextReply("Sorry, I could not do that.")]
        async with FakeOpenAIServer(script) as server:
            result = await Assistant(_backend(server), robot.tools).turn("projector on")
        assert [o.is_error for o in result.outcomes] == [True, True]
        assert json.loads(result.outcomes[0].text)["error"] == "invalid_arguments"
        assert "not valid JSON" in json.loads(result.outcomes[1].text)["message"]
        assert robot.sim is not None and robot.sim.state.projector_on is False


async def test_step_bound_ends_the_turn_with_words() -> None:
    async with connect_robot(SIM) as robot:
        looks = itertools.cycle(["get_battery_state", "get_robot_pose", "get_projector_state"])

        def reply(request: RecordedRequest) -> ToolCallReply | TextReply:
            if request.tool_names:  # keeps calling tools for as long as it is offered any
                return ToolCallReply((ScriptedCall(next(looks), {}),))
            return TextReply("My battery is fine.")

        from robovoice.llm.fake_server import CallbackReply

        async with FakeOpenAIServer([], default=CallbackReply(reply)) as server:
            result = await Assistant(_backend(server), robot.tools, max_steps=3).turn("battery?")
            requests = list(server.requests)
        assert len(requests) == 3 and requests[-1].tool_names == []
        assert len(result.calls) == 2 and result.reply == "My battery is fine."


async def test_a_repeated_look_up_is_not_run_again_and_the_model_answers_at_once() -> None:
    """chatml-function-calling's strict call grammar made the model repeat its look-up for as
    long as tools were offered; the repeat is not run and the next step offers no tools."""
    async with connect_robot(SIM) as robot:
        def reply(request: RecordedRequest) -> ToolCallReply | TextReply:
            if request.tool_names:
                return ToolCallReply((ScriptedCall("get_battery_state", {}),))
            result = next(m for m in reversed(request.messages) if m["role"] == "tool")  # the look-up's
            percent = json.loads(result["content"])["value"]["percent"]
            return TextReply(f"My battery is at {percent:.0f} percent.")

        from robovoice.llm.fake_server import CallbackReply

        async with FakeOpenAIServer([], default=CallbackReply(reply)) as server:
            result = await Assistant(_backend(server), robot.tools, max_steps=4).turn("how much battery do you have?")
            requests = list(server.requests)
        assert [bool(r.tool_names) for r in requests] == [True, True, False]
        assert [c.name for c in result.calls] == ["get_battery_state"]
        assert result.reply.startswith("My battery is at ") and result.reply.endswith(" percent.")


async def test_a_call_written_as_text_on_the_no_tools_step_is_not_run_and_the_turn_ends_with_words() -> None:
    """Seen from llama-cpp-python's chatml-function-calling server: offered no tools, the model
    still wrote `functions.NAME:` as its answer. That call must not run, and the person must not
    be left with silence."""
    async with connect_robot(SIM) as robot:
        from robovoice.llm.fake_server import CallbackReply

        def reply(request: RecordedRequest) -> ToolCallReply | TextReply:
            if request.tool_names:
                return ToolCallReply((ScriptedCall("get_battery_state", {}),))
            return TextReply('functions.navigate_to:\n{"target": "kitchen"}')

        events: list[TurnEvent] = []
        async with FakeOpenAIServer([], default=CallbackReply(reply)) as server:
            result = await Assistant(_backend(server), robot.tools, max_steps=2, observer=events.append).turn(
                "how much battery do you have?")
        assert [c.name for c in result.calls] == ["get_battery_state"]  # the drive written as text never ran
        assert robot.sim is not None and robot.sim.state.moving is False
        spoken = [e.text for e in events if isinstance(e, SentenceReady)]
        # the look-up's own phrase says what was found
        assert len(spoken) == 1 and re.fullmatch(r"My battery is at \d+ percent(?:, and I am charging)?\.",
                                                  spoken[0]), spoken
        assert result.reply == spoken[0]


async def test_failover_to_a_second_server_then_fallback_when_all_are_dead() -> None:
    async with connect_robot(SIM) as robot:
        events: list[TurnEvent] = []
        async with FakeOpenAIServer([ErrorReply(500, "GPU on fire")]) as edge, \
                FakeOpenAIServer([TextReply("Hello from the cloud.")]) as cloud:
            chain = FailoverBackend([OpenAICompatBackend(edge.base_url, edge.model, name="edge"),
                                     OpenAICompatBackend(cloud.base_url, cloud.model, name="cloud")],
                                    backoff=Backoff(60, 2, 60))
            _OPENED.extend(b for b in chain.backends if isinstance(b, OpenAICompatBackend))
            assistant = Assistant(chain, robot.tools, observer=events.append)
            first = await assistant.turn("hello")
            assert first.reply == "Hello from the cloud." and not first.fell_back
            assert [h.healthy for h in chain.health()] == [False, True]
        # Both servers are gone now: the turn ends, quickly, with the spoken fallback.
        second = await assistant.turn("hello again")
        assert second.fell_back and second.reply == FALLBACK_MESSAGE
        assert any(isinstance(e, BackendFailed) for e in events)
        assert [e.text for e in events if isinstance(e, SentenceReady)][-1] == FALLBACK_MESSAGE


async def test_stalled_backend_misses_its_first_token_deadline() -> None:
    async with connect_robot(SIM) as robot:
        from robovoice.llm.base import Deadlines

        async with FakeOpenAIServer([TextReply("late", pacing=Pacing(first_token_delay_s=5))]) as server:
            backend = OpenAICompatBackend(server.base_url, server.model,
                                          deadlines=Deadlines(connect_s=1, first_token_s=0.3, idle_s=1, total_s=5))
            _OPENED.append(backend)
            result = await Assistant(FailoverBackend([backend]), robot.tools).turn("hi")
        assert result.fell_back and result.metrics.as_dict()["finished"] < 3000


async def test_history_is_bounded_and_starts_at_a_user_message() -> None:
    async with connect_robot(SIM) as robot:
        async with FakeOpenAIServer([], default=TextReply("Okay.")) as server:
            assistant = Assistant(_backend(server), robot.tools, max_history_messages=4)
            for i in range(5):
                await assistant.turn(f"message {i}")
            last = list(server.requests)[-1]
        assert 1 <= len(assistant.history) <= 4 and assistant.history[0].role == "user"
        assert [m["content"] for m in last.messages if m["role"] == "user"][-1] == "message 4"
        assert "message 0" not in json.dumps(last.messages)


async def test_history_is_cut_in_halves_so_prompts_mostly_grow_by_appending() -> None:
    """Prefix caching on the model side pays off only while each prompt extends the last one."""
    async with connect_robot(SIM) as robot, FakeOpenAIServer([], default=TextReply("Okay.")) as server:
        assistant = Assistant(_backend(server), robot.tools, max_history_messages=8)
        for i in range(12):
            await assistant.turn(f"message {i}")
            assert len(assistant.history) <= 8 and assistant.history[0].role == "user"
        prompts = [r.messages for r in server.requests]
    extended = sum(later[: len(earlier)] == earlier for earlier, later in itertools.pairwise(prompts))
    # 12 turns of 2 messages, a window of 8 cut to 4 when exceeded: the history is cut before
    # every third turn once full, so 8 of the 11 later prompts extend the one before
    assert extended == 8  # sliding by one turn once the window is full: only the first 4
    assert all(len(p) <= 1 + 8 + 1 for p in prompts)  # system + history + the new user message
