"""Running the console for a test: the embedded sim robot, a scripted model, the real server."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager
from dataclasses import dataclass
from typing import Any

from websockets.asyncio.client import ClientConnection

from robovoice.assistant.connect import connect_robot
from robovoice.config import RobotConfig
from robovoice.console.serve import console_server
from robovoice.console.service import Console
from robovoice.console.voice import VoiceBridge
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedReply
from robovoice.llm.openai_compat import OpenAICompatBackend

SIM = RobotConfig(address="sim://?speed=50")
BOUND_S = 30.0


@dataclass
class Running:
    console: Console
    base: str  # http://127.0.0.1:PORT
    server: FakeOpenAIServer

    @property
    def ws_base(self) -> str:
        return self.base.replace("http://", "ws://", 1)


@asynccontextmanager
async def running_console(script: list[ScriptedReply] | None = None, *, default: ScriptedReply | None = None,
                          token: str | None = None, robot: RobotConfig = SIM,
                          voice: Callable[[Any, Any], VoiceBridge] | None = None) -> AsyncIterator[Running]:
    async with connect_robot(robot) as connection, FakeOpenAIServer(script or [], default=default) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        bridge = voice(backend, connection.tools) if voice is not None else None
        console = Console(connection.tools, backend, voice=bridge, robot_name=robot.address)
        task = asyncio.create_task(console.run())
        try:
            async with console_server(console, token=token) as endpoint:
                yield Running(console, f"http://127.0.0.1:{endpoint.port}", server)
        finally:
            task.cancel()
            await asyncio.gather(task, return_exceptions=True)
            await backend.aclose()


async def next_message(ws: ClientConnection, accept: Callable[[dict[str, Any]], bool],
                       timeout: float = BOUND_S) -> dict[str, Any]:
    """The next message `accept` takes (others are skipped), within `timeout`."""
    async with asyncio.timeout(timeout):
        while True:
            message = json.loads(await ws.recv())
            if accept(message):
                return dict(message)
