"""Speech that searches for its words (assistant/word_finding.py): plain code, no model. The
utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.word_finding import words_found


@pytest.mark.parametrize(("said", "found"), [
    ("Go... go plug in.", "go plug in."),
    ("Then... then call Ben.", "then call Ben."),
    ("Switch on the pro... projector.", "Switch on the projector."),
    ("The ki-kitchen, please.", "The kitchen, please."),
    ("Projector. On.", "Projector on."),
    ("Stop the... the talking now.", "end the call now."),
    ("I'd like to... I'd like to see Anna.", "I'd like to see Anna."),
    ("Come, come to the kitchen.", "Come to the kitchen."),
    # nothing searched for: as said
    ("Turn off the projector. On second thoughts, leave it.", "Turn off the projector. On second thoughts, leave it."),
    ("A co-operative robot.", "A co-operative robot."),
    ("Stop talking about Ben.", "Stop talking about Ben."),
    ("Stop, stop, the cat!", "Stop, stop, the cat!"),  # each stop a stop ("the cat" no step after one)
])
def test_each_word_searched_for_is_said_once_as_found(said: str, found: str) -> None:
    assert words_found(said) == found


@pytest.mark.parametrize(("said", "steps"), [
    ("Kitchen. Then... then call Ben.", ("Kitchen", "call Ben")),
    ("Bedroom first. Then the pro... projector. On. Then call Ben.", ("Bedroom first", "the projector on", "call Ben")),
    ("Bye bye. Stop the... the talking.", ("end the call",)),
    ("Go, go to the hallway, and when you get there... call Clara.", ("Go to the hallway", "call Clara")),
    ("I want to... I want to ring Ben.", ("I want to ring Ben",)),
])
def test_they_are_read_as_the_words_found(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


def test_a_room_or_the_dock_said_alone_is_worded_as_a_drive_for_the_model() -> None:
    intent = read_request("First bathroom. Then, uh, hallway. Then... home.")
    assert intent.worded_steps == ("go to the bathroom", "hallway", "go back to your charging dock")
