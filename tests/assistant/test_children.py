"""How children talk to the robot (`dialects._childish`, `amend.go_list`, `neighbours._counted`): a dare
asks, "my guy" names nobody, a called-out list of places is the way to go, a count is
no step. Plain code, no model; made-up utterances, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "steps"), [
    ("Betcha can't get to the bathroom before me! Three, two, one...", ("get to the bathroom before me",)),
    ("Kitchen, my dude. Go.", ("go to kitchen",)),
    ("Aight so first the bedroom, then the projector on.", ("go to the bedroom", "the projector on")),
    ("Bedroom, then bathroom, then the kitchen! Race you!", ("Bedroom", "bathroom", "the kitchen")),
])
def test_a_childs_request_is_read_as_asked(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).worded_steps == steps


@pytest.mark.parametrize("said", [
    "Kitchen, then the bedroom, that's where I looked.",  # no "!": talk
    "Pull up a chair, Grandpa.",
    "I bet you can't even ring Ben, ha.",
])
def test_talk_that_sounds_like_it_asks_nothing(said: str) -> None:
    assert not read_request(said).asks_action
