"""A place named right after the robot is called by name is asked for (`neighbours._after_its_name`,
through `intent.read_request` and `gate.refusal`), with the sim robot's own manifests: plain code,
no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.reading import ClauseKind
from tests.assistant.test_where_and_which import _reason


@pytest.mark.parametrize(("text", "place"), [
    ("Oi robot, kitchen, the kettle's whistling.", "kitchen"),
    ("Robot. The bedroom. I'm off for a nap.", "bedroom"),
    ("Right, Jarvis, front door, someone's knocking.", "front door"),
])
def test_a_place_after_the_robots_name_is_asked(text: str, place: str) -> None:
    assert read_request(text).asks_action
    assert _reason(text, "navigate_to", {"target": place}) is None


@pytest.mark.parametrize("text", [
    "Robot, good morning.",
    "Robot, thank you.",
    "Jarvis, Anna. Anna, say hello to the robot.",  # an introduction as likely as a call
    "Robot, the kitchen is a tip today.",  # a statement of its own
])
def test_a_greeting_a_name_or_talk_after_it_asks_nothing(text: str) -> None:
    intent = read_request(text)
    assert not intent.asks_action, [(c.text, c.kind) for c in intent.clauses]
    assert intent.refusal is ClauseKind.STATEMENT


@pytest.mark.parametrize(("text", "step"), [
    ("Um, the bathroom. You go and have a look, the tap is dripping.", "go to the bathroom and have a look"),
    ("The hallway. You go and you look.", "go to the hallway and look"),
    ("Kitchen. Go and have a look.", "go to kitchen and have a look"),
    ("Bathroom. Go. Now.", "go to bathroom"),
])
def test_a_going_without_where_takes_the_place_said_before(text: str, step: str) -> None:
    assert read_request(text).worded_steps[0] == step


@pytest.mark.parametrize("text", ["The bedroom. Go on then.", "Clara. You go and ring her.", "Anyway, go and charge.",
                                  "Kitchen. Go and check the oven is off."])
def test_a_going_with_a_way_or_after_a_name_stays_as_said(text: str) -> None:
    assert not read_request(text).worded_steps[0].startswith("go to")
