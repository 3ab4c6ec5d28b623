"""A node that joins mid-conversation: the MCP server announces `notifications/tools/list_changed`
and the assistant's next turn offers the new tool to the model, which can call it.

The embedded sim robot starts without its projector node; the model is the fake OpenAI server,
scripted to call the projector's tool once it is offered."""

from __future__ import annotations

import logging

import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.loop import Assistant
from robovoice.config import RobotConfig
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedCall, ScriptedReply, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.mcp_server.runtime import wait_for_tools
from robovoice.sim import NODE_NAMES, start_sim_robot

from ..waiting import BOUND_S, until

WITHOUT_PROJECTOR = RobotConfig(
    address="sim://?speed=50&nodes=" + ",".join(n for n in NODE_NAMES if n != "projector"))


async def test_a_node_joining_mid_conversation_gives_the_next_turn_its_tool(
        caplog: pytest.LogCaptureFixture) -> None:
    script: list[ScriptedReply] = [
        TextReply("I have no projector I could switch on."),
        ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),)),
    ]
    caplog.set_level(logging.INFO, logger="robovoice.assistant.robot_tools")
    async with connect_robot(WITHOUT_PROJECTOR) as robot, FakeOpenAIServer(script) as server:
        assert robot.side is not None
        assistant = Assistant(OpenAICompatBackend(server.base_url, server.model), robot.tools)

        first = await assistant.turn("Switch on the projector, please.")
        assert first.calls == () and "set_projector_power" not in server.requests[0].tool_names
        assert "navigate_to" in server.requests[0].tool_names

        caplog.clear()
        projector = await start_sim_robot(robot.side.middleware, speed=50, nodes=["projector"])
        try:
            await wait_for_tools(robot.side.server, names=["set_projector_power"], timeout=BOUND_S)
            await until(lambda: "robot tool list changed" in caplog.text, what="tools/list_changed at the client")

            second = await assistant.turn("The projector is there now. Switch it on.")
        finally:
            await projector.stop()

    assert [(c.name, c.arguments) for c in second.calls] == [("set_projector_power", {"on": True})]
    assert not second.outcomes[0].is_error, second.outcomes[0].text
    assert "set_projector_power" in server.requests[1].tool_names
    assert len(server.requests) == 2  # turn 1; turn 2: the call (its success phrase is the answer)
    assert second.reply == "The projector is now on."
    # The conversation went on: the second turn's request still holds the first exchange.
    assert server.requests[1].messages[1]["content"] == "Switch on the projector, please."
