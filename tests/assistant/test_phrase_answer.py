"""A tool's own success phrase as the answer, instead of a second model step (issue 12): a
scripted model behind a real HTTP server, the embedded sim behind the real MCP server, with
the sim's manifests given success phrases."""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path
from typing import Any

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.events import SentenceReady, ToolCalled, ToolReturned, TurnEvent
from robovoice.assistant.intent import read_request
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.assistant.phrase import phrase_answer
from robovoice.config import RobotConfig
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedCall, ScriptedReply, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.manifest.voice import VoiceDecl, VoicePhrases, fill, result_fields

# success phrases by node and tool, as in the sim's own manifests
PHRASES = {
    ("navigation", "navigate_to"): "I am at the {arrived} now.",
    ("projector", "set_projector_power"): "The projector {changed:is now|was already} {on:on|off}.",
    ("communication", "start_video_call"): "I am in a video call with {contact} now.",
}


def manifests(tmp: Path, phrases: dict[tuple[str, str], str]) -> Path:
    """The sim's manifests with `phrases` as the tools' success phrases."""
    shipped = resources.files("robovoice.sim") / "manifests"
    for node in shipped.iterdir():
        if not node.is_dir():
            continue
        manifest: dict[str, Any] = json.loads((node / "mcp.json").read_text(encoding="utf-8"))
        for tool in manifest.get("tools", []):
            phrase = phrases.get((node.name, tool["name"]))
            if phrase is not None:
                voice = tool.setdefault("voice", {})
                voice.setdefault("say", {})["success"] = phrase
        (tmp / node.name).mkdir()
        (tmp / node.name / "mcp.json").write_text(json.dumps(manifest), encoding="utf-8")
    return tmp


def call(name: str, **arguments: object) -> ToolCallReply:
    return ToolCallReply((ScriptedCall(name, arguments),))


async def run(
    tmp: Path, script: list[ScriptedReply], *texts: str, phrases: dict[tuple[str, str], str] = PHRASES,
) -> tuple[list[TurnResult], FakeOpenAIServer, list[TurnEvent], Assistant]:
    events: list[TurnEvent] = []
    robot_config = RobotConfig(address="sim://?speed=50", manifests=manifests(tmp, phrases))
    async with connect_robot(robot_config) as robot, FakeOpenAIServer(script) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            assistant = Assistant(backend, robot.tools, observer=events.append)
            results = [await assistant.turn(text) for text in texts]
        finally:
            await backend.aclose()
    return results, server, events, assistant


async def test_a_filled_phrase_is_the_answer_and_the_model_is_not_asked_again(tmp_path: Path) -> None:
    script: list[ScriptedReply] = [call("navigate_to", target="kitchen"), TextReply("You're welcome.")]
    (result, thanks), server, events, assistant = await run(tmp_path, script, "Please go to the kitchen.",
                                                            "Thank you.")
    assert result.reply == "I am at the kitchen now."
    assert [e.text for e in events if isinstance(e, SentenceReady)][:1] == ["I am at the kitchen now."]
    assert "phrase_answer" in result.metrics.marks
    assert result.metrics.marks["phrase_answer"] >= result.metrics.marks["tool_result:navigate_to"]
    # one model step for the drive; the next request is the next turn's, with a coherent history
    assert len(server.requests) == 2 and thanks.reply == "You're welcome."
    roles = [(m["role"], m.get("content")) for m in server.requests[1].messages[1:]]
    assert roles[0] == ("user", "Please go to the kitchen.")
    assert roles[1][0] == "assistant" and roles[2][0] == "tool"
    assert roles[3:] == [("assistant", "I am at the kitchen now."), ("user", "Thank you.")]
    assert assistant.history[-1].text == "You're welcome."


async def test_a_phrase_that_does_not_fill_leaves_the_answer_to_the_model(tmp_path: Path) -> None:
    # the result has no "brightness": the phrase cannot be said completely, so it is not said
    phrases = {("projector", "set_projector_power"): "The projector shines at {brightness} percent."}
    script: list[ScriptedReply] = [call("set_projector_power", on=True), TextReply("The projector is on.")]
    (result,), server, events, _ = await run(tmp_path, script, "Switch the projector on.", phrases=phrases)
    assert len(server.requests) == 2 and result.reply == "The projector is on."
    assert "phrase_answer" not in result.metrics.marks
    assert [e.text for e in events if isinstance(e, SentenceReady)] == ["The projector is on."]


async def test_a_failed_call_without_a_failure_phrase_gets_the_model(tmp_path: Path) -> None:
    script: list[ScriptedReply] = [call("navigate_to", target="garage"),
                                   TextReply("I don't know a garage. Which room do you mean?")]
    (result,), server, _, _ = await run(tmp_path, script, "Drive to the garage.")
    assert result.outcomes[0].error == "unknown_target"
    assert len(server.requests) == 2 and result.reply.endswith("Which room do you mean?")


async def test_a_compound_request_says_each_phrase_and_goes_on(tmp_path: Path) -> None:
    script: list[ScriptedReply] = [call("navigate_to", target="kitchen"), call("set_projector_power", on=True),
                                   TextReply("never asked for")]
    (result,), server, events, _ = await run(tmp_path, script,
                                             "Go to the kitchen and then switch the projector on.")
    assert [c.name for c in result.calls] == ["navigate_to", "set_projector_power"]
    assert result.reply == "I am at the kitchen now. The projector is now on."
    assert [e.text for e in events if isinstance(e, SentenceReady)] == ["I am at the kitchen now.",
                                                                         "The projector is now on."]
    # the model was asked twice: once per thing asked, never just to word a result
    assert len(server.requests) == 2
    second = server.requests[1].messages
    assert second[-2] == {"role": "assistant", "content": "I am at the kitchen now."}
    assert server.requests[1].last_user_text == "Now do the next thing I asked: switch the projector on."


async def test_a_question_about_the_result_gets_the_model(tmp_path: Path) -> None:
    script: list[ScriptedReply] = [call("navigate_to", target="kitchen"),
                                   TextReply("I am in the kitchen; it was 5.3 metres.")]
    (result,), server, events, _ = await run(tmp_path, script, "Go to the kitchen. How far was it?")
    assert len(server.requests) == 2 and result.reply == "I am in the kitchen; it was 5.3 metres."
    assert "I am at the kitchen now." not in [e.text for e in events if isinstance(e, SentenceReady)]


async def test_a_refused_call_gets_the_model_with_its_hint(tmp_path: Path) -> None:
    script: list[ScriptedReply] = [call("start_video_call", contact="Ben"), TextReply("He rang at ten.")]
    (result,), server, _, _ = await run(tmp_path, script, "When did my son Ben phone?")
    assert result.outcomes[0].error == "not_requested"
    assert len(server.requests) == 2 and result.reply == "He rang at ten."


async def test_a_call_refused_on_talk_alone_is_answered_by_the_robot(tmp_path: Path) -> None:
    script: list[ScriptedReply] = [call("start_video_call", contact="Ben"), TextReply("never asked for")]
    (result,), server, _, _ = await run(tmp_path, script, "My son Ben phoned earlier.")
    assert result.outcomes[0].error == "not_requested"
    assert len(server.requests) == 1 and result.reply == "I see."


async def test_an_ability_question_about_the_call_made_is_answered_by_the_robot(tmp_path: Path) -> None:
    script: list[ScriptedReply] = [call("set_projector_power", on=True), TextReply("never asked for")]
    (result,), server, _, _ = await run(tmp_path, script, "Just so I know, could you put the projector on yourself?")
    assert result.outcomes[0].error == "not_requested" and len(server.requests) == 1
    assert result.reply == "Yes, I can do that when you ask me to."


def test_the_rule_reads_the_request_and_the_step() -> None:
    voice = {"navigate_to": VoiceDecl(say=VoicePhrases(success="I am at the {arrived} now.")),
             "get_battery_state": VoiceDecl(say=VoicePhrases(success="My battery is at {percent:.0f} percent."))}
    drive = (ToolCalled("1", "navigate_to", {"target": "kitchen"}),
             ToolReturned("1", "navigate_to", "{}", False, 1.0, None, {"arrived": "kitchen", "distance_m": 5.3}))
    battery = (ToolCalled("2", "get_battery_state", {}),
               ToolReturned("2", "get_battery_state", "{}", False, 1.0, None, {"percent": 81.8}))
    asked = read_request("Go to the kitchen")
    assert phrase_answer(asked, voice, [drive]) == "I am at the kitchen now."
    assert phrase_answer(read_request("Can you go to the kitchen? Is it far?"), voice, [drive]) is None
    assert phrase_answer(None, voice, [drive]) is None  # audio: no words to read
    # a look-up before acting never ends the turn, even with a phrase
    assert phrase_answer(asked, voice, [battery], read_only={"get_battery_state"}) is None
    assert phrase_answer(asked, voice, [drive, battery], read_only={"get_battery_state"}) is None
    # ... but while the turn goes on with more asked, the look-up's phrase says what was found,
    # even for a question ("how charged are you, then go to the kitchen")
    compound = read_request("How charged are you? Then go to the kitchen.")
    assert phrase_answer(compound, voice, [battery], read_only={"get_battery_state"},
                         continuing=True) == "My battery is at 82 percent."
    assert phrase_answer(compound, voice, [battery], read_only={"get_battery_state"}) is None
    # an action's step still gets the model for a question about it ("go there; how far was it?")
    assert phrase_answer(read_request("Go to the kitchen. How far was it?"), voice, [drive], continuing=True) is None


def test_a_fresh_snapshots_message_fills_a_phrase_and_a_stale_one_does_not() -> None:
    fresh = {"value": {"percent": 80.3, "charging": True}, "stamp": 1.0, "age_s": 0.01, "stale": False}
    template = "My battery is at {percent:.0f} percent{charging:, and I am charging|}."
    assert fill(template, result_fields({}, fresh)) == "My battery is at 80 percent, and I am charging."
    assert fill(template, result_fields({}, {**fresh, "stale": True})) is None


def test_yes_no_fields_pick_a_word_and_results_win_over_arguments() -> None:
    template = "The projector {changed:is now|was already} {on:on|off}."
    assert fill(template, {"on": True, "changed": False}) == "The projector was already on."
    assert fill(template, {"on": False, "changed": True}) == "The projector is now off."
    assert fill("{on:on|off}", {"on": "yes"}) is None  # not a yes/no value: no phrase
    fields = result_fields({"target": "Kitchen", "speed": 1}, {"target": "kitchen", "note": "", "path": [1, 2]})
    assert fields == {"target": "kitchen", "speed": 1}
