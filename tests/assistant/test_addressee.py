"""Sentences said to someone else in the room (assistant/addressee.py), polite forms, a
checklist's numbers, "…, the bedroom instead", and a stop or a want said of someone else
(intent, lexicon.plain, amend.instead)."""

from __future__ import annotations

import pytest

from robovoice.assistant.addressee import set_aside
from robovoice.assistant.intent import read_request
from robovoice.assistant.reading import ClauseKind


@pytest.mark.parametrize(("text", "steps"), [
    ("Robot, ring Clara. Ben, don't you touch that.", ("ring Clara",)),  # not a second call, to Ben
    ("No, Ben, not you. Robot, go to the bedroom.", ("go to the bedroom",)),
    ("Jarvis, put the projector on. No, Ben, not you, I was talking to the robot.", ("put the projector on",)),
    ("Mum, can you ring Ben? Robot, go to the kitchen.", ("go to the kitchen",)),
    ("Gran, go and sit down. Switch the projector on, please.", ("Switch the projector on",)),
])
def test_a_sentence_said_to_someone_else_asks_the_robot_nothing(text: str, steps: tuple[str, ...]) -> None:
    intent = read_request(text)
    assert intent.steps == steps
    assert any(c.kind is ClauseKind.STATEMENT and c.text.endswith((".", "?")) for c in intent.clauses)


@pytest.mark.parametrize("text", [
    # said only to someone else
    "No, Clara, I'll call you later.",
    "Ben, you ought to ring your sister Anna tonight.",
    "Dad, could you switch the projector off when you go up?",
    # talk, or a question about ability, beside the formal requests
    "Perhaps you might have left it in the kitchen.",
    "Can you make video calls?",
    "Can you look at things far away?",
    # a reason after a no
    "Don't go to the bathroom, the floor is wet.",
    "Don't ring Anna, she is busy.",
    "Not the bathroom, thanks.",
    # a stop said of something else, what someone else is to do
    "Oh, this cold is driving me mad, I can't stop sneezing.",
    "My knees won't stop aching today.",
    "Don't hang up yet, I want Anna to see the garden.",
    "I need Clara to know the hallway light is broken.",
])
def test_nothing_is_asked(text: str) -> None:
    assert not read_request(text).asks_action


@pytest.mark.parametrize(("text", "steps"), [
    ("Anna, please.", ("Anna",)),  # an answer to "Whom shall I call?"
    ("Anna, then Ben.", None),  # a list of whom, not an address
    ("Kitchen, go on then.", ("go on then",)),  # a place first is no name
    ("Och, forget the bedroom, take me to the kitchen.", ("take me to the kitchen",)),  # an exclamation
    ("Hey Travis, go to the kitchen, please.", ("go to the kitchen",)),  # the wake word misheard
    ("Ben, stop that!", ("stop that",)),  # a spoken stop is always for the robot
    ("Ring Dr. Weber. Thanks.", ("Ring Dr. Weber",)),  # a title's full stop ends no sentence
])
def test_what_still_reads_as_said_to_the_robot(text: str, steps: tuple[str, ...] | None) -> None:
    if steps is not None:
        assert read_request(text).steps == steps
    assert set_aside(text)[1] == ()


@pytest.mark.parametrize("text", [
    "Might you go to the kitchen for me?",
    "May I ask you to call Ben?",
    "Would it be too much trouble to switch the projector on?",
    "Would it be terribly inconvenient for you to ring my daughter?",
    "Perhaps you might ring Clara for me.",
    "I'd be ever so grateful if you might consider taking yourself off to the hallway.",
    "Could you take a gander at the bathroom for me?",
    "Can I get you to switch the projector off?",
])
def test_the_most_formal_requests_ask(text: str) -> None:
    assert [c.kind for c in read_request(text).clauses] == [ClauseKind.REQUEST]


def test_having_the_robot_to_oneself_asks_nothing() -> None:
    assert not read_request("Can I have you to myself for a minute?").asks_action


@pytest.mark.parametrize("text", ["Hallway, and quick about it.", "Bedroom. Chop chop.", "Kitchen, sharpish!"])
def test_haste_after_a_bare_place_asks_for_it(text: str) -> None:
    assert read_request(text).steps == (text.split(",")[0].split(".")[0],)


def test_haste_after_a_request_is_no_step_of_its_own() -> None:
    assert read_request("Go to the kitchen and switch the projector on, quick!").steps == (
        "Go to the kitchen", "switch the projector on")


def test_tell_you_what_opens_talk_and_asks_nothing() -> None:
    assert not read_request("Tell you what, that was a lovely film last night.").asks_action
    assert read_request("I'll tell you what, ring Ben.").steps == ("ring Ben",)


def test_a_checklists_numbers_are_its_order() -> None:
    assert read_request("Item one: the bedroom. Item two: the projector off.").steps == \
        ("first the bedroom", "the projector off")
    assert read_request("Number one, projector on. Number two, call Ben.").steps == ("first projector on", "call Ben")
    assert read_request("Call number one.").steps == ("Call number one",)


@pytest.mark.parametrize(("text", "steps"), [
    ("Don't bother with the bathroom, just the bedroom.", ("just the bedroom",)),
    ("Not the bathroom, the bedroom.", ("the bedroom",)),
    ("Don't go to the bathroom, the bedroom instead.", ("the bedroom instead",)),
])
def test_what_is_wanted_instead_of_what_was_declined(text: str, steps: tuple[str, ...]) -> None:
    intent = read_request(text)
    assert intent.steps == steps
    assert intent.clauses[0].kind is ClauseKind.NEGATED


@pytest.mark.parametrize(("text", "steps"), [
    # with the robot called by name in another sentence, a name anywhere says whom a sentence is for
    ("Tom, pop the kettle on, would you? And you, robot, off you go to the front door.",
     ("off you go to the front door",)),
    ("Sit yourself down, Margaret, I'll sort it. Robot, ring Clara.", ("ring Clara",)),
    ("Robot, go to the kitchen. Then ring my son, Ben.", ("go to the kitchen", "ring my son Ben")),  # who he is
    ("Robot, call Anna. Ben, stop that.", ("call Anna", "stop that")),  # not a call to Ben
    ("Hypothetically, can you call Ben?", ()),  # an adverb is no name
    ("Harry, switch the telly off, would you? Robot, you ring Anna.", ("ring Anna",)),  # "you" after its name
])
def test_a_name_beside_the_robots_name_says_whom_a_sentence_is_for(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


def test_a_lists_heading_said_as_a_sentence_is_no_step() -> None:
    assert read_request("Two things. Projector on, then video call Dr. Weber.").steps == \
        ("Projector on", "video call Dr. Weber")


@pytest.mark.parametrize(("text", "steps"), [
    ("Why won't you stop?", ("Why won't you stop",)),
    ("I want you to go to the kitchen.", ("I want you to go to the kitchen",)),
    ("I want to call Ben.", ("I want to call Ben",)),
    # a stop is never taken back: "cancel that" after one cancels the drive
    ("Stop, stop! Cancel that and go back to your charger instead.",
     ("Stop", "Cancel that", "go back to your charger instead")),
])
def test_what_still_asks(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # text test v132: the speaker turns from someone in the room to the robot inside one sentence
    ("Priya, hold on — no, robot, you go to the hallway, the postman is here.", ("go to the hallway",)),
    ("Ben, put the kettle on, robot, ring Clara.", ("ring Clara",)),
])
def test_a_turn_to_the_robot_inside_a_sentence_is_for_it(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps
