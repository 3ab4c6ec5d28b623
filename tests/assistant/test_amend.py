"""Corrections said without "no", and a list of places sent off with a bare "go" (assistant/amend.py)."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.reading import ClauseKind


@pytest.mark.parametrize(("text", "steps"), [
    ("Ring Clara, sorry, I mean Ben, and then go to the hallway.", ("I mean Ben", "go to the hallway")),
    ("Ring Clara, I mean Ben.", ("I mean Ben",)),
    ("Go to the bathroom, or rather the bedroom.", ("or rather the bedroom",)),
    ("Head to the kitchen, correction, the living room.", ("the living room",)),
    ("Turn the projector on, I mean off.", ("Turn the projector off",)),  # a state takes the request's words
    ("Go to the kitchen. Wait, the bathroom.", ("the bathroom",)),  # a bare "wait" before the value
    ("Call Anna. Hang on, Ben.", ("Ben",)),
    ("Go to the kitchen. Oh wait, the bedroom I mean.", ("the bedroom",)),  # the "I mean" said after
])
def test_a_value_said_after_a_correction_word_puts_the_last_request_right(text: str, steps: tuple[str, ...]) -> None:
    intent = read_request(text)
    assert intent.steps == steps
    assert intent.clauses[0].kind is ClauseKind.NEGATED


@pytest.mark.parametrize(("text", "steps"), [
    ("Go to the kitchen, sorry, then the bedroom.", ("Go to the kitchen", "the bedroom")),  # one more step
    ("Go to the kitchen, sorry, the bedroom after that.", ("Go to the kitchen", "the bedroom after that")),
    ("Go to the kitchen please. Sorry, my dear.", ("Go to the kitchen please",)),
    ("Call Ben, sorry for the bother.", ("Call Ben",)),
    ("Go to the kitchen, wait by the front door.", ("Go to the kitchen", "wait by the front door")),  # a step
    ("Go to the kitchen... wait, and then the bathroom.", ("Go to the kitchen", "the bathroom")),
    ("Go to the kitchen. Hang on, call Ben.", ("Go to the kitchen", "call Ben")),  # a request of its own
    ("Switch the projector on. Wait, the bedroom.", ("Switch the projector on",)),  # no drive to put right
    ("Switch the projector on. Sorry, I'm muddled today.", ("Switch the projector on",)),
    # put right already: only what the "not" names is taken back
    ("Go to the bedroom, then the kitchen, sorry, not the kitchen, I meant the living room.",
     ("Go to the bedroom", "I meant the living room")),
    # the same place said again is no correction
    ("Go to the bathroom, no, sorry, the hallway, I meant the hallway.", ("the hallway",)),
])
def test_what_is_no_correction_leaves_the_requests_as_they_were(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


def test_i_mean_it_takes_nothing_back() -> None:
    assert read_request("Go to the kitchen, I mean it.").clauses[0].kind is ClauseKind.REQUEST


def test_places_in_a_then_list_sent_off_with_a_bare_go_are_its_steps() -> None:
    assert read_request("Hallway, then the kitchen, then the front door. Off you go.").steps == (
        "Hallway", "the kitchen", "the front door")
    assert read_request("Evening round: bathroom, then bedroom, then back on your dock. Go.").steps == (
        "bathroom", "bedroom", "back on your dock")  # the heading stays talk
    assert read_request("Bathroom first, then back to your charger. Go now.").steps == (
        "Bathroom first", "back to your charger")  # the "go" is no step of its own
    # no "go", or a "go on" that may only say "carry on": talk stays talk; a route of bare places
    # and nothing else is asked (text test v63: "front door, after that the kitchen"), not as a question
    assert read_request("Kitchen, then bedroom.").steps == ("Kitchen", "bedroom")
    assert not read_request("My glasses... kitchen, then the bedroom?").asks_action
    assert not read_request("Ben rang, then Clara.").asks_action
    assert read_request("Ben phoned, then Clara. Off you go.").steps == ("Off you go",)  # news, a name: no place
    assert read_request("I went to the kitchen, then the bedroom. Go on.").steps == ("Go on",)


def test_places_in_a_then_list_ending_on_the_way_back_are_its_steps() -> None:
    assert read_request("Kitchen, then hallway, then back to base.").steps == ("Kitchen", "hallway", "back to base")
    assert read_request("Anna rang, then Ben, and then back to dock.").steps == ("back to dock",)  # names stay talk
    assert read_request("Bathroom, then the living room, please.").steps == ("Bathroom", "the living room")


def test_a_corrected_step_is_worded_with_the_request_it_puts_right() -> None:
    intent = read_request("Three jobs: go to the hallway, switch the projector on, then phone Clara, no, Ben.")
    assert intent.steps == ("go to the hallway", "switch the projector on", "Ben")
    assert intent.worded_steps == ("go to the hallway", "switch the projector on", "phone Ben")
    assert read_request("Go to the kitchen, then the bedroom.").worded_steps == ("Go to the kitchen", "the bedroom")


def test_a_corrected_place_is_worded_as_the_drive_without_its_courtesy() -> None:
    assert read_request("Could you go to the hallway, no wait, what am I saying, the front door.").worded_steps == (
        "go to the front door",)
    assert read_request("Leave the projector for now, just ring Ben.").worded_steps == ("just ring Ben",)  # a verb


@pytest.mark.parametrize(("text", "worded"), [
    ("I'm in the bathroom, by the basin. Would you come over here to me?", ("come to the bathroom",)),
    ("We're sitting in the living room with tea. Come and join us.", ("come to the living room",)),
    ("I am at the front door. Get over here.", ("come to the front door",)),
    ("Come here, please.", ("Come here",)),  # nowhere said: the model asks where
    ("I'm in the kitchen. Go to the bedroom.", ("Go to the bedroom",)),  # a place of its own
    ("Ben is in the kitchen. Come here.", ("Come here",)),  # where someone else is
])
def test_here_is_worded_as_where_the_person_said_they_are(text: str, worded: tuple[str, ...]) -> None:
    assert read_request(text).worded_steps == worded


@pytest.mark.parametrize(("text", "steps"), [
    # audio test v113: "no hallway" with no comma took the hallway back, and "go there" drove to the bathroom
    ("bathroom, no hallway, hallway, go there.", ("go there",)),
    ("The kitchen? No. Go to the hallway.", ("Go to the hallway",)),
])
def test_a_room_said_alone_then_no_then_another_room_takes_the_first_back(text: str, steps: tuple[str, ...]) -> None:
    intent = read_request(text)
    assert intent.steps == steps
    assert intent.clauses[0].kind is ClauseKind.NEGATED
