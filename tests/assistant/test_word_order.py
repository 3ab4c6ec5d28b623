"""The verb after its object ("Bathroom you go", "Doctor Weber call"), a "hold off" that takes back
the request before it, the speaker's own "let me …", a switch said thing first, and a Korean
honorific after a name: plain code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.dialects import as_standard
from robovoice.assistant.intent import read_request
from robovoice.sim.communication import find_contact


@pytest.mark.parametrize(("said", "standard"), [
    ("Living room you go, then Clara call.", "go to the living room, then call Clara."),
    ("Charger go now, please.", "go to the charger now, please."),
    ("Doctor Weber ring please.", "ring Doctor Weber please."),
    # no object first: left as said
    ("Let it go.", "Let it go."), ("Off you go!", "Off you go!"), ("Ready, steady, go!", "Ready, steady, go!"),
    ("Good call, that.", "Good call, that."), ("Ben will call.", "Ben will call."), ("Ok go.", "Ok go."),
])
def test_the_verb_after_its_object_is_put_first(said: str, standard: str) -> None:
    assert as_standard(said) == standard


@pytest.mark.parametrize("said", [
    "Ring Clara... um. Hold off. Let me put my teeth in first.",
    "Go to the front door. Hold off on that for now.",
])
def test_hold_off_takes_back_the_request_before_it(said: str) -> None:
    assert read_request(said).steps == ()


def test_hold_off_before_a_request_leaves_it() -> None:
    assert read_request("Hold off, go to the bedroom.").steps == ("go to the bedroom",)


def test_the_speakers_own_let_me_is_no_step() -> None:
    assert read_request("Let me find my slippers, then go to the hallway.").steps == ("go to the hallway",)
    assert read_request("Let me talk to Ben.").asks_action  # a call asked for


def test_a_switch_said_thing_first_is_a_step() -> None:
    steps = read_request("Ring Anna, then telly off for my nap, then go to the bedroom.").steps
    assert len(steps) == 3 and "off" in steps[1]
    assert not read_request("The projector on the shelf is dusty.").asks_action


@pytest.mark.parametrize(("said", "name"), [("Clara-ssi", "Clara"), ("Ben samchon", "Ben"), ("Anna-ya", "Anna")])
def test_a_korean_honorific_after_a_name_is_the_name(said: str, name: str) -> None:
    found = find_contact(said)
    assert found is not None and found.name == name


@pytest.mark.parametrize(("said", "steps"), [
    ("Ring Ben for me, Maria.", ("Ring Ben for me",)),  # said to Maria: no second call
    ("Ring Clara, then Ben.", ("Ring Clara", "Ben")),
    ("Call Anna, no, Ben.", ("Call Ben",)),
])
def test_a_name_said_last_after_a_call_with_its_person_is_whom_it_is_said_to(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).worded_steps == steps
