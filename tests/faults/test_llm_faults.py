"""Faults on the LLM side, injected on purpose, through the whole tool loop: the real MCP
server over the sim robot (with its audit log), the real OpenAI-compatible backend behind the
failover chain, and a real HTTP server speaking vLLM's wire format that misbehaves on script.

Each: the robot ends in a known state (it did what was completed, nothing else, and stands
still), the user gets the short spoken explanation, the assistant recovers on the next turn,
and the audit log is valid JSON Lines with every completed call in it."""

from __future__ import annotations

import functools
import inspect
import json
from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import Any

import pytest

from robovoice.assistant.connect import RobotConnection, connect_robot
from robovoice.assistant.events import BackendFailed, SentenceReady, TurnEvent
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.config import RobotConfig
from robovoice.llm.base import Deadlines
from robovoice.llm.failover import FALLBACK_MESSAGE, Backoff, FailoverBackend
from robovoice.llm.fake_server import (
    ErrorReply,
    FakeOpenAIServer,
    Pacing,
    ScriptedCall,
    ScriptedReply,
    TextReply,
    ToolCallReply,
)
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.mcp_server.audit import read_audit

SIM = RobotConfig(address="sim://?speed=50")
FAST = Deadlines(connect_s=2, first_token_s=0.5, idle_s=0.5, total_s=10)
DRIVE = ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),))
RECOVERED = TextReply("I'm back. What can I do?")
# a question about the result: the model words the answer after the drive (a plain "go to the
# kitchen" is answered by the drive's own success phrase, with no second model step to break)
ASKED_AFTER_THE_DRIVE = "go to the kitchen. Is it tidy?"


class Turns:
    """An assistant over `robot` and one fake server, recording events."""

    def __init__(self, robot: RobotConnection, server: FakeOpenAIServer) -> None:
        self.backend = OpenAICompatBackend(server.base_url, server.model, deadlines=FAST)
        self.events: list[TurnEvent] = []
        self.assistant = Assistant(FailoverBackend([self.backend], backoff=Backoff(0.01, 1, 0.01)), robot.tools,
                                   observer=self.events.append)

    async def turn(self, text: str) -> TurnResult:
        return await self.assistant.turn(text)

    def spoken(self) -> list[str]:
        return [e.text for e in self.events if isinstance(e, SentenceReady)]


def with_robot(test: Callable[..., Awaitable[None]]) -> Callable[..., Awaitable[None]]:
    """Run `test` with ``robot=``: the sim robot served in this process with its audit log in
    ``tmp_path``. Opened inside the test, not in a fixture: anyio's cancel scopes must be entered
    and left in the same task, and pytest-asyncio runs fixture teardown in another."""

    @functools.wraps(test)
    async def run(**kwargs: Any) -> None:
        async with connect_robot(SIM, audit_log=kwargs["tmp_path"] / "audit.jsonl") as robot:
            await test(robot=robot, **kwargs)

    signature = inspect.signature(test)
    run.__signature__ = signature.replace(  # type: ignore[attr-defined]  # pytest reads it for fixtures
        parameters=[p for p in signature.parameters.values() if p.name != "robot"])
    return run


def _audit(tmp_path: Path) -> list[tuple[str, str]]:
    """(tool, outcome) of every audited call; the file must be entirely valid JSON Lines."""
    path = tmp_path / "audit.jsonl"
    lines = path.read_text(encoding="utf-8").splitlines() if path.exists() else []
    return [(r["tool"], r["outcome"]) for r in map(json.loads, lines)]


async def _expect_explained_then_recovered(turns: Turns, first: TurnResult) -> None:
    assert first.fell_back and first.reply.endswith(FALLBACK_MESSAGE)
    assert turns.spoken()[-1] == FALLBACK_MESSAGE  # the short explanation is spoken
    assert any(isinstance(e, BackendFailed) for e in turns.events)
    again = await turns.turn("are you there?")
    assert not again.fell_back and again.reply == RECOVERED.text


@pytest.mark.parametrize("hard", [False, True], ids=["closed", "reset"])
@with_robot
async def test_stream_closed_mid_sentence_after_a_drive(robot: RobotConnection, tmp_path: Path, hard: bool) -> None:
    cut = TextReply("I have arrived in the kitchen and I am", chunk_chars=4,
                    pacing=Pacing(cut_after_chunks=3, cut_hard=hard))
    async with FakeOpenAIServer([DRIVE, cut, RECOVERED]) as server:
        turns = Turns(robot, server)
        first = await turns.turn(ASKED_AFTER_THE_DRIVE)
        assert [c.name for c in first.calls] == ["navigate_to"] and not first.outcomes[0].is_error
        await _expect_explained_then_recovered(turns, first)
        await turns.backend.aclose()
    assert robot.sim is not None
    state = robot.sim.state
    assert state.nearest_place == "kitchen" and not state.moving  # the completed drive, then standing still
    assert _audit(tmp_path) == [("navigate_to", "ok")]


@with_robot
async def test_stream_closed_inside_the_tool_call_arguments_calls_nothing(robot: RobotConnection,
                                                                          tmp_path: Path) -> None:
    broken = ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),), arg_chunk_chars=3,
                           pacing=Pacing(cut_after_chunks=3))
    async with FakeOpenAIServer([broken, RECOVERED]) as server:
        turns = Turns(robot, server)
        first = await turns.turn("go to the kitchen")
        assert first.calls == ()
        await _expect_explained_then_recovered(turns, first)
        await turns.backend.aclose()
    assert robot.sim is not None and robot.sim.state.nearest_place == "charging dock" and not robot.sim.state.moving
    assert _audit(tmp_path) == []


@pytest.mark.parametrize("pacing", [Pacing(first_token_delay_s=30), Pacing(headers_delay_s=30),
                                    Pacing(stall_after_chunks=2, stall_s=30)], ids=["prefill", "headers", "mid"])
@with_robot
async def test_a_stalled_server_is_given_up_within_its_deadline(robot: RobotConnection, tmp_path: Path,
                                                                pacing: Pacing) -> None:
    async with FakeOpenAIServer([DRIVE, TextReply("Here I am in the kitchen.", pacing=pacing), RECOVERED]) as server:
        turns = Turns(robot, server)
        first = await turns.turn(ASKED_AFTER_THE_DRIVE)
        assert first.metrics.as_dict()["finished"] < 5000  # bounded by the deadlines, not the 30 s stall
        await _expect_explained_then_recovered(turns, first)
        await turns.backend.aclose()
    assert robot.sim is not None and robot.sim.state.nearest_place == "kitchen" and not robot.sim.state.moving
    assert _audit(tmp_path) == [("navigate_to", "ok")]


@pytest.mark.parametrize("status", [500, 429, 503])
@with_robot
async def test_an_error_status_is_explained_and_the_next_turn_recovers(robot: RobotConnection, tmp_path: Path,
                                                                       status: int) -> None:
    replies: list[ScriptedReply] = [ErrorReply(status, "overloaded, try later", "RateLimitError"), RECOVERED]
    async with FakeOpenAIServer(replies) as server:
        turns = Turns(robot, server)
        first = await turns.turn("what's my battery?")
        assert first.calls == ()
        await _expect_explained_then_recovered(turns, first)
        await turns.backend.aclose()
    assert _audit(tmp_path) == []


@pytest.mark.parametrize("arguments", ['{"target": "kitch', "not json at all", '["kitchen"]', '{"target": 7}',
                                       '{"target": "kitchen", "target": "garage"', ""])
@with_robot
async def test_malformed_tool_call_json_becomes_a_tool_error_and_the_model_recovers(
        robot: RobotConnection, tmp_path: Path, arguments: str) -> None:
    script: list[ScriptedReply] = [ToolCallReply((ScriptedCall("navigate_to", arguments),)),
                                   TextReply("Sorry, where should I go?")]
    async with FakeOpenAIServer(script) as server:
        turns = Turns(robot, server)
        result = await turns.turn("go somewhere")
        requests = list(server.requests)
        await turns.backend.aclose()
    assert not result.fell_back and result.reply == "Sorry, where should I go?"
    assert [o.is_error for o in result.outcomes] == [True]
    error = json.loads(result.outcomes[0].text)
    assert error["error"] in ("invalid_arguments", "unknown_target") and error["message"]
    tool_message = requests[1].messages[-1]  # the model was told what was wrong
    assert tool_message["role"] == "tool" and error["error"] in tool_message["content"]
    assert robot.sim is not None and robot.sim.state.nearest_place == "charging dock" and not robot.sim.state.moving
    assert all(outcome == "error" for _, outcome in _audit(tmp_path))
    assert read_audit(tmp_path / "audit.jsonl").skipped == []
