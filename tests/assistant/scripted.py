"""Assistant turns against the embedded sim robot, with a scripted model behind a real HTTP
server (`FakeOpenAIServer`): `scripted_sim` for tests that also look at the robot or take
several turns, `scripted_turn` for tests that look only at one turn's result and at what the
model was sent."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterable
from contextlib import asynccontextmanager

from robovoice.assistant.connect import RobotConnection, connect_robot
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.config import RobotConfig
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedReply
from robovoice.llm.openai_compat import OpenAICompatBackend

SIM = RobotConfig(address="sim://?speed=50")


@asynccontextmanager
async def scripted_sim(
    script: Iterable[ScriptedReply],
) -> AsyncIterator[tuple[RobotConnection, FakeOpenAIServer, OpenAICompatBackend]]:
    """The sim robot, the scripted model's server (its `requests`: what the model was sent) and
    a backend that talks to it, closed on exit."""
    async with connect_robot(SIM) as robot, FakeOpenAIServer(script) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            yield robot, server, backend
        finally:
            await backend.aclose()


async def scripted_turn(script: Iterable[ScriptedReply], text: str) -> tuple[TurnResult, FakeOpenAIServer]:
    """The turn's result for `text`, and the server (its `requests`: what the model was sent)."""
    async with scripted_sim(script) as (robot, server, backend):
        return await Assistant(backend, robot.tools).turn(text), server
