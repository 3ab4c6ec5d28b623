"""Spoken confirmation (issue 11): a call that cannot be taken back, made on words that may be
misheard, is held and asked about; the answer is read locally. A scripted model behind a real
HTTP server, the embedded sim behind the real MCP server with its shipped manifests (whose
start_video_call declares "Shall I call {contact}?")."""

from __future__ import annotations

from typing import Any

import pytest

from robovoice.assistant.confirm import DECLINED, Confirmations, confirm_question, reply_to_question
from robovoice.assistant.connect import connect_robot
from robovoice.assistant.gate import CONFIRM, NOT_REQUESTED
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.config import RobotConfig
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedCall, ScriptedReply, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.manifest.voice import VoiceDecl, VoicePhrases


def call(name: str, **arguments: object) -> ToolCallReply:
    return ToolCallReply((ScriptedCall(name, arguments),))


async def conversation(
    script: list[ScriptedReply], *turns: tuple[str, bool], clock: list[float] | None = None,
) -> tuple[list[TurnResult], int, dict[str, Any]]:
    """Each (text, doubtful) turn in one conversation; the results, the number of model
    requests, and the robot's call state read from the sim afterwards."""
    async with connect_robot(RobotConfig(address="sim://?speed=50")) as robot, FakeOpenAIServer(script) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            assistant = Assistant(backend, robot.tools)
            if clock is not None:
                assistant.confirmations = Confirmations(clock=lambda: clock[0], window_s=30.0)
            results = []
            for text, doubtful in turns:
                results.append(await assistant.turn(text, doubtful=doubtful))
                if clock is not None:
                    clock[0] += 40.0  # the next answer comes after the window
            state = await robot.tools.call("get_call_state", {}, None)
        finally:
            await backend.aclose()
    assert state.structured is not None
    value = state.structured.get("value")
    assert isinstance(value, dict)
    return results, len(server.requests), value


def in_call(state: dict[str, Any]) -> bool:
    return state["in_call"] is True


@pytest.mark.parametrize("text", ["Yes.", "Yes, please.", "yeah go ahead", "Please do.", "Okay.", "Sure, thanks.",
                                  "Hey Jarvis, yes please.", "Yes, call her."])
def test_yes_words(text: str) -> None:
    assert reply_to_question(text) is True


@pytest.mark.parametrize("text", ["No.", "No, thank you.", "Nope.", "Don't.", "Not now.", "Never mind.",
                                  "No, leave it."])
def test_no_words(text: str) -> None:
    assert reply_to_question(text) is False


@pytest.mark.parametrize("text", ["No, call Ben.", "Yes and then go to the kitchen.", "What?", "Go to the kitchen.",
                                  "Call Anna.", "", "I don't know"])
def test_anything_else_is_no_answer(text: str) -> None:
    assert reply_to_question(text) is None


def test_the_question_is_filled_from_the_arguments_or_not_asked() -> None:
    voice = {"start_video_call": VoiceDecl(say=VoicePhrases(confirm="Shall I call {contact}?"))}
    assert confirm_question(voice, "start_video_call", {"contact": "Anna"}) == "Shall I call Anna?"
    assert confirm_question(voice, "start_video_call", {}) is None  # cannot be said whole: not asked
    assert confirm_question(voice, "navigate_to", {"target": "kitchen"}) is None  # declares none


async def test_a_doubtful_call_is_held_asked_about_and_run_on_yes_without_the_model() -> None:
    script: list[ScriptedReply] = [call("start_video_call", contact="Anna"), TextReply("never used")]
    (asked, yes), requests, state = await conversation(script, ("Hey Jarvis, call Anna.", True),
                                                       ("Yes, please.", False))
    assert asked.reply == "Shall I call Anna?"
    assert asked.outcomes[0].error == NOT_REQUESTED
    assert asked.outcomes[0].result is not None and asked.outcomes[0].result["details"]["reason"] == CONFIRM
    assert [c.name for c in yes.calls] == ["start_video_call"] and not yes.outcomes[0].is_error
    assert yes.reply == "I am in a video call with Anna now."
    assert requests == 1  # the yes was read locally
    assert in_call(state)


async def test_no_drops_the_held_call() -> None:
    script: list[ScriptedReply] = [call("start_video_call", contact="Anna"), TextReply("never used")]
    (_, no), requests, state = await conversation(script, ("call Anna", True), ("No, don't.", False))
    assert no.reply == DECLINED and not no.calls
    assert requests == 1
    assert not in_call(state)


async def test_a_yes_after_the_window_is_no_answer_and_goes_to_the_model() -> None:
    script: list[ScriptedReply] = [call("start_video_call", contact="Anna"), TextReply("Yes what?")]
    (_, late), requests, state = await conversation(script, ("call Anna", True), ("Yes.", False), clock=[0.0])
    assert late.reply == "Yes what?" and not late.calls
    assert requests == 2
    assert not in_call(state)


async def test_a_new_request_drops_the_held_call() -> None:
    script: list[ScriptedReply] = [call("start_video_call", contact="Anna"), call("navigate_to", target="kitchen"),
                                   TextReply("On my way."), TextReply("Hm?")]
    (_, other, yes), _, state = await conversation(script, ("call Anna", True), ("Go to the kitchen.", False),
                                                   ("Yes.", False))
    assert [c.name for c in other.calls] == ["navigate_to"]
    assert not yes.calls  # nothing is held any more: the yes went to the model
    assert not in_call(state)


async def test_a_clear_transcript_runs_the_call_unasked() -> None:
    script: list[ScriptedReply] = [call("start_video_call", contact="Anna"), TextReply("Calling.")]
    (result,), requests, state = await conversation(script, ("call Anna", False))
    assert not result.outcomes[0].is_error and result.reply == "I am in a video call with Anna now." and requests == 1
    assert in_call(state)


async def test_in_a_compound_request_the_rest_runs_and_the_question_comes_last() -> None:
    script: list[ScriptedReply] = [call("start_video_call", contact="Anna"), call("set_projector_power", on=True),
                                   TextReply("The projector is on.")]
    (result,), _, state = await conversation(script, ("Call Anna and then switch on the projector.", True))
    assert [c.name for c in result.calls] == ["start_video_call", "set_projector_power"]
    assert not result.outcomes[1].is_error
    assert result.reply.endswith("Shall I call Anna?")
    assert not in_call(state)


async def test_a_tool_without_a_question_runs_in_doubt() -> None:
    script: list[ScriptedReply] = [call("set_projector_power", on=True), TextReply("unused")]
    (result,), _, _ = await conversation(script, ("switch the projector on", True))
    assert [c.name for c in result.calls] == ["set_projector_power"] and not result.outcomes[0].is_error


async def test_a_drive_in_doubt_asks_first_and_a_yes_drives() -> None:
    """Audio v32: "go to the... no. Never mind." heard as "go to the door, let my mind." in doubt
    drove to the front door. A drive declares a question now: held, asked, run on a yes."""
    script: list[ScriptedReply] = [call("navigate_to", target="front door"), TextReply("unused")]
    (asked, answered), _, _ = await conversation(script, ("go to the door, let my mind.", True), ("Yes.", False))
    assert asked.outcomes[0].is_error and asked.reply.endswith("Shall I go to the front door?")
    assert [c.name for c in answered.calls] == ["navigate_to"] and not answered.outcomes[0].is_error


async def test_a_doubtful_call_to_someone_the_robot_does_not_list_asks_which_one() -> None:
    """Audio v16's compound-6: "ring Anna" heard as "ring gunner" made the robot ask "Shall I call
    Gunner?", a question about nobody it knows. A doubtful call naming none of the contacts the
    tool lists is refused as unclear: the robot asks which one it lists; typed, it runs and the
    robot's own error says whom it can call."""
    script: list[ScriptedReply] = [call("start_video_call", contact="Gunner"), TextReply("never used")]
    (asked,), requests, state = await conversation(script, ("Hey Jarvis, ring gunner.", True))
    assert asked.reply == "Which one do you mean: Anna, Ben, Clara or Dr. Weber?"
    assert asked.outcomes[0].result is not None and asked.outcomes[0].result["details"]["reason"] == "unclear"
    assert requests == 1 and not in_call(state)
    script = [call("start_video_call", contact="Gunner"), TextReply("I cannot call Gunner.")]
    (typed,), _, _ = await conversation(script, ("Ring Gunner.", False))
    assert typed.outcomes[0].error == "unknown_contact"


async def test_which_one_is_asked_after_the_rest_of_a_compound_request() -> None:
    """Audio v16's compound-6 read again: the drive ran and said its phrase; the doubtful call to
    "gunner" was refused, the model only repeated the drive's phrase (not said twice), and the
    turn ended without anyone asking which one was meant. (The first step is the projector here: a
    drive in doubt is itself asked about now, `test_a_drive_in_doubt_asks_first_and_a_yes_drives`.)"""
    script: list[ScriptedReply] = [call("set_projector_power", on=True), call("start_video_call", contact="Gunner"),
                                   TextReply("The projector is now on."), TextReply("never used")]
    (result,), _, state = await conversation(script, ("First switch the projector on, and ring gunner.", True))
    assert result.reply == "The projector is now on. Which one do you mean: Anna, Ben, Clara or Dr. Weber?"
    assert not in_call(state)
