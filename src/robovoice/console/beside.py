"""The console beside another command (`robovoice demo --console`): the page served while the
command runs, showing the robot and the command's voice pipeline events as they happen."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager

from robovoice.assistant.events import notify
from robovoice.assistant.robot_tools import RobotTools
from robovoice.console.serve import console_server
from robovoice.console.service import Console
from robovoice.llm.base import LLMBackend
from robovoice.voice.events import PipelineEvent, VoiceObserver

Wrap = Callable[[VoiceObserver | None], VoiceObserver | None]


@asynccontextmanager
async def console_beside(tools: RobotTools, backend: LLMBackend, *, port: int | None, say: Callable[[str], None],
                         robot_name: str = "sim://") -> AsyncIterator[Wrap]:
    """Serve the console on 127.0.0.1:`port` (None: no console) for the block; yields a function
    that wraps the command's pipeline observer so the page gets the same events."""
    if port is None:
        yield lambda observer: observer
        return
    console = Console(tools, backend, robot_name=robot_name)
    watching = asyncio.create_task(console.run(), name="console-beside")
    try:
        async with console_server(console, port=port) as endpoint:
            say(f"watch it in the console: {endpoint.url}")

            def wrap(observer: VoiceObserver | None) -> VoiceObserver:
                async def both(event: PipelineEvent) -> None:
                    await notify(observer, event)
                    console.observe(event, "voice")

                return both

            yield wrap
    finally:
        watching.cancel()
        await asyncio.gather(watching, return_exceptions=True)
