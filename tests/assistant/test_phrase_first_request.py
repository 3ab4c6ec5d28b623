"""`Assistant.first_request`: what the first model step of a turn would send, for a speculative
prefill — compared with what a real turn sends over the wire (a scripted model behind a real
HTTP server, the embedded sim behind the real MCP server)."""

from __future__ import annotations

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.loop import Assistant
from robovoice.config import RobotConfig
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedReply, TextReply
from robovoice.llm.openai_compat import OpenAICompatBackend

SIM = RobotConfig(address="sim://?speed=50")


async def test_first_request_is_what_the_first_model_step_sends() -> None:
    script: list[ScriptedReply] = [TextReply("Hello! How can I help?"), TextReply("Which one first?")]
    async with connect_robot(SIM) as robot, FakeOpenAIServer(script) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            assistant = Assistant(backend, robot.tools)
            await assistant.turn("Hello there")  # a history, so the request carries it
            before = assistant.history
            # a compound request: the first step carries the "one thing at a time" line too
            text = "Go to the kitchen and then switch the projector on."
            messages, tools = await assistant.first_request(text)
            assert assistant.history == before  # no side effect on the conversation
            await assistant.turn(text)
        finally:
            await backend.aclose()
    sent = server.requests[1]
    assert [m.to_openai() for m in messages] == sent.messages
    assert [t.to_openai() for t in tools] == sent.body["tools"]
    assert sent.messages[1]["content"] == "Hello there" and sent.messages[-1]["content"].startswith("One thing")


async def test_first_request_offers_a_look_up_step_only_the_read_only_tools_as_the_turn_does() -> None:
    async with connect_robot(SIM) as robot, FakeOpenAIServer([TextReply("I am near the dock.")] * 3) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            assistant = Assistant(backend, robot.tools)
            text = "Tell me where you are, then come to the kitchen."
            messages, tools = await assistant.first_request(text)
            await assistant.turn(text)
        finally:
            await backend.aclose()
    sent = server.requests[0]
    assert [m.to_openai() for m in messages] == sent.messages
    assert [t.to_openai() for t in tools] == sent.body["tools"]
    assert "get_robot_pose" in sent.tool_names and "navigate_to" not in sent.tool_names
