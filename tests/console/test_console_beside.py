"""`robovoice demo --console`: another command's pipeline events reach the page as they happen."""

from __future__ import annotations

import httpx

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.events import ToolCalled, ToolReturned
from robovoice.console.beside import console_beside
from robovoice.llm.fake_server import FakeOpenAIServer
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.events import PipelineEvent, TranscriptReady, VoiceTurnFinished, WakeWordHeard

from .console_testkit import BOUND_S, SIM


async def test_the_demos_events_are_shown_by_a_console_beside_it() -> None:
    said: list[str] = []
    printed: list[PipelineEvent] = []
    async with connect_robot(SIM) as robot, FakeOpenAIServer() as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        async with console_beside(robot.tools, backend, port=0, say=said.append) as watched:
            observer = watched(printed.append)
            assert observer is not None
            for event in (WakeWordHeard(0.97, 1.2), TranscriptReady("go to the kitchen", 420.0),
                          ToolCalled("c1", "navigate_to", {"target": "kitchen"}),
                          ToolReturned("c1", "navigate_to", "{}", False, 12.0, None, {"arrived": "kitchen"}),
                          VoiceTurnFinished(1, None, False, {"first_audio": 1500.0})):
                result = observer(event)
                if result is not None:
                    await result
            url = said[0].split()[-1]
            async with httpx.AsyncClient(base_url=url, timeout=BOUND_S) as http:
                state = (await http.get("/api/state")).json()
                audit = (await http.get("/api/audit")).json()["records"]
        await backend.aclose()
    assert len(printed) == 5  # the command's own observer still gets everything
    (turn,) = state["turns"]
    assert [e["kind"] for e in turn["events"]] == ["WakeWordHeard", "TranscriptReady", "ToolCalled", "ToolReturned",
                                                   "VoiceTurnFinished"]
    assert turn["latency_ms"] == {"first_audio": 1500.0} and not turn["open"]
    assert [(r["tool"], r["source"]) for r in audit] == [("navigate_to", "voice")]
    async with console_beside(robot.tools, backend, port=None, say=said.append) as unwatched:
        assert unwatched(printed.append) == printed.append
