"""Swedish, Norwegian, Danish and Finnish turns said in English (assistant/nordic.py): plain code, no
model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.nordic import from_nordic


@pytest.mark.parametrize(("said", "english"), [
    ("Nå, make the projector on, tack.", "switch the projector on, thank you."),
    ("No niin, then we ring Ben.", "then let's ring Ben."),
    ("Eventually you could go to the bathroom.", "could you go to the bathroom."),
    ("You can lay on the call now.", "You can hang up the call now."),
    ("You shall go to the kitchen.", "please go to the kitchen."),
    ("Ring to Clara, kiitos.", "Ring Clara, thank you."),
    ("Be so good and drive to the hallway.", "please drive to the hallway."),
    # English as it is
    ("You shall not pass.", "You shall not pass."),
    ("Eventually I will get a new one.", "Eventually I will get a new one."),
    ("Jo, can you help?", "Jo, can you help?"),  # a name too
    ("And now we go live to the front door of Number Ten.", "And now we go live to the front door of Number Ten."),
])
def test_nordic_turns_are_said_as_english_says_them(said: str, english: str) -> None:
    assert from_nordic(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Joo, then we call Ben.", ("let's call Ben",)),
    ("Jo, you shall drive to the bedroom, the cat is there.", ("please drive to the bedroom",)),
    ("Eventually you could take yourself to the hallway, if it is not too much trouble.",
     ("could you take yourself to the hallway",)),
    ("Stop the call with Ben and put the projector off.", ("end the call with Ben", "put the projector off")),
])
def test_they_are_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
