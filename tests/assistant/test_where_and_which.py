"""Where to stay is no halt, and a value named only in talk is not the one asked for
(`gate.staying`, `gate._named_in_talk`, through `gate.refusal`), with the sim robot's own
manifests: plain code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.gate import OTHER, refusal
from robovoice.assistant.halting import halts
from robovoice.assistant.intent import read_request
from tests.assistant.test_fit import SPECS, VOICE


def _reason(text: str, tool: str, arguments: dict[str, object]) -> str | None:
    body = refusal(read_request(text), SPECS[tool], arguments, (), VOICE, tools=list(SPECS.values()))
    return None if body is None else str(body["details"]["reason"])


@pytest.mark.parametrize("text", [
    "Head over to the bathroom and wait there.",
    "Off to the front door, then stay there till the postman's been.",
    "Wait for me in the living room, would you?",
    "Go to the kitchen, stay by the fridge.",
])
def test_where_to_wait_is_no_stop(text: str) -> None:
    for tool in ("stop_robot", "cancel_navigation"):
        assert _reason(text, tool, {}) == OTHER, tool
    assert not halts(read_request(text))


@pytest.mark.parametrize("text", ["Wait there!", "Stay where you are.", "Hold on, stay there a second."])
def test_wait_there_alone_still_halts(text: str) -> None:
    assert halts(read_request(text))  # the loop runs the stop while the robot moves


@pytest.mark.parametrize(("text", "tool", "arguments"), [
    ("Pop into the bathroom, the bedroom's a tip anyway.", "navigate_to", {"target": "bedroom"}),
    ("Off to your charger now, you've been sat by the front door all day.", "navigate_to", {"target": "front door"}),
    ("Ring Clara please, Ben never picks up.", "start_video_call", {"contact": "Ben"}),
])
def test_a_value_named_only_in_talk_is_not_the_one_asked(text: str, tool: str, arguments: dict[str, object]) -> None:
    assert _reason(text, tool, arguments) is not None  # ("Ben never picks up" reads as declined)


@pytest.mark.parametrize(("text", "tool", "arguments"), [
    ("Pop into the bathroom, the bedroom's a tip anyway.", "navigate_to", {"target": "bathroom"}),
    ("Ring Clara please, Ben never picks up.", "start_video_call", {"contact": "Clara"}),
    ("The parcel is at the front door. Go there, please.", "navigate_to", {"target": "front door"}),
    ("I'm in the bedroom, come to me.", "navigate_to", {"target": "bedroom"}),
])
def test_the_value_asked_for_still_runs(text: str, tool: str, arguments: dict[str, object]) -> None:
    assert _reason(text, tool, arguments) is None


@pytest.mark.parametrize(("text", "refused"), [
    ("Keep the photo right next to the projector.", True),  # where it is, no switch (audio test v99, misheard)
    ("Put my glasses on top of the projector, love.", True),
    ("Switch on the projector behind the sofa.", False),
    ("Put the projector on, it's next to the telly.", False),
])
def test_a_thing_named_as_where_something_is_is_not_switched(text: str, refused: bool) -> None:
    assert (_reason(text, "set_projector_power", {"on": True}) is not None) is refused
