"""Which way a switch goes (`assistant.polarity`, through `gate.refusal`), with the sim robot's own
projector manifest: plain code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.gate import WRONG_WAY, checked, own_words, refusal, said_after
from robovoice.assistant.intent import read_request
from robovoice.assistant.loop import Assistant
from robovoice.assistant.polarity import wrong_way
from robovoice.llm.base import ToolSpec
from robovoice.llm.fake_server import TextReply
from tests.assistant.scripted import scripted_sim
from tests.assistant.test_fit import SPECS, VOICE, WORDS
from tests.assistant.test_judgement_loop import call, made

PROJECTOR = "set_projector_power"


def _refused(text: str, on: bool) -> str | None:
    body = refusal(read_request(text), SPECS[PROJECTOR], {"on": on}, (), VOICE, tools=list(SPECS.values()))
    return None if body is None else str(body["details"]["reason"])


@pytest.mark.parametrize(("text", "on"), [
    ("Could you switch the projector off now, please?", True),
    ("Go to the kitchen, then put the projector on.", False),
    ("Turn the projector on, I mean off.", True),  # the request as corrected
    ("That screen is too bright, turn it off.", True),  # "it": the screen named before
    ("Flick the gizmo off. The projector, I mean.", True),  # what the switch is, said after it
])
def test_a_switch_sent_the_other_way_round_is_refused(text: str, on: bool) -> None:
    assert _refused(text, on) == WRONG_WAY


@pytest.mark.parametrize(("text", "on"), [
    ("Could you switch the projector off now, please?", False),
    ("Go to the kitchen, then put the projector on.", True),
    ("Come on, switch the projector off.", False),  # "come on" is its own clause, about nothing
    ("Projector on, then off you go to the living room.", True),  # that "off" is the drive's
    ("Turn the projector off and on again.", True),  # both words: nothing to go by
    ("Turn the projector off and on again.", False),
    ("Douse the projector.", True),  # neither word: the model's choice, as before
])
def test_a_switch_the_right_way_or_not_said_either_way_runs(text: str, on: bool) -> None:
    assert _refused(text, on) is None


def test_the_words_come_from_the_arguments_description() -> None:
    gripper = {"type": "object", "properties": {"open": {
        "type": "boolean", "description": "true to open the gripper, false to close it"}}}
    asked = read_request("Please close the gripper.")
    assert wrong_way(asked, "set_gripper", gripper, {"open": True}, ["hand"]) == "close"
    assert wrong_way(asked, "set_gripper", gripper, {"open": False}, ["hand"]) is None
    plain = {"type": "object", "properties": {"on": {"type": "boolean", "description": "the new state"}}}
    assert wrong_way(read_request("Switch the projector off."), PROJECTOR, plain, {"on": True}, WORDS[PROJECTOR]) \
        is None  # no pair of opposite words to check against


def test_the_robot_has_its_own_words_when_the_model_has_none() -> None:
    body = refusal(read_request("Switch the projector off."), ToolSpec(PROJECTOR, SPECS[PROJECTOR].description,
                                                                       SPECS[PROJECTOR].parameters),
                   {"on": True}, (), VOICE, tools=list(SPECS.values()))
    assert body is not None and body["details"]["reason"] == WRONG_WAY and own_words(body) is None
    assert said_after(WRONG_WAY) == "Sorry, I got that the wrong way round. Could you say it again?"


async def test_in_the_loop_a_switch_sent_the_wrong_way_is_sent_the_way_the_words_say() -> None:
    """The projector is on; "switch it off" and the model sends ``on: true``: the robot is sent
    ``on: false`` (what the person asked), and is never asked to switch it on."""
    async with scripted_sim([call("set_projector_power", on=True), TextReply("The projector is off.")]) as (
            robot, _server, backend):
        await robot.apply_setup("projector_on")
        result = await Assistant(backend, robot.tools).turn("Could you switch the projector off, please?")
        assert robot.sim is not None and not robot.sim.state.projector_on
    assert made(result) == [("set_projector_power", None)]
    assert result.calls[0].arguments == {"on": False}
    assert "wrong way" not in result.reply


def test_a_switch_is_sent_the_way_the_words_say_only_where_they_ask_for_it() -> None:
    spec = ToolSpec(PROJECTOR, SPECS[PROJECTOR].description, SPECS[PROJECTOR].parameters)
    assert checked(read_request("Switch the projector off."), spec, {"on": True}, (), VOICE,
                   tools=list(SPECS.values())) == ({"on": False}, None)
    assert checked(read_request("Switch the projector off."), spec, {"on": False}, (), VOICE,
                   tools=list(SPECS.values())) == ({"on": False}, None)
    arguments, refused = checked(read_request("Don't switch the projector off."), spec, {"on": True}, (), VOICE,
                                 tools=list(SPECS.values()))
    assert arguments == {"on": True} and refused is not None and refused["details"]["reason"] != WRONG_WAY
    arguments, refused = checked(read_request("Switch the projector off and on again."), spec, {"on": True}, (),
                                 VOICE, tools=list(SPECS.values()))
    assert arguments == {"on": True} and refused is None  # both words: nothing to go by
