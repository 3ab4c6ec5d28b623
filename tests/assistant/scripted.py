"""One assistant turn against the embedded sim robot, with a scripted model behind a real HTTP
server (`FakeOpenAIServer`): for tests that look only at the turn's result and at what the
model was sent."""

from __future__ import annotations

from collections.abc import Iterable

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.config import RobotConfig
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedReply
from robovoice.llm.openai_compat import OpenAICompatBackend

SIM = RobotConfig(address="sim://?speed=50")


async def scripted_turn(script: Iterable[ScriptedReply], text: str) -> tuple[TurnResult, FakeOpenAIServer]:
    """The turn's result for `text`, and the server (its `requests`: what the model was sent)."""
    async with connect_robot(SIM) as robot, FakeOpenAIServer(script) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            return await Assistant(backend, robot.tools).turn(text), server
        finally:
            await backend.aclose()
