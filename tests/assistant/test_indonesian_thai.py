"""Requests said with Indonesian, Malay or Thai inside English (assistant/indonesian_thai.py): plain
code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.indonesian_thai import from_indonesian_thai
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "english"), [
    ("Tolong go to the kitchen ya.", "please go to the kitchen."),
    ("Bedroom, please khrap.", "Bedroom, please."),
    ("Jangan call Clara, nanti saja.", "don't call Clara, later."),
    ("Makasih ya, call Om Budi sekarang", "thank you, call Budi now"),
    # no word only they have: left as said ("ya" is English's "you" there)
    ("See ya later, Om.", "See ya later, Om."),
    ("Call Pak, ya?", "Call Pak, ya?"),
])
def test_indonesian_malay_and_thai_are_put_in_english(said: str, english: str) -> None:
    assert from_indonesian_thai(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Hallway, please kha. Someone is at the door.", ("Hallway",)),
    ("Tolong ring Clara, but before that turn the projector off ya.", ("turn the projector off", "please ring Clara")),
    ("Jangan go to the kitchen sekarang.", ()),
])
def test_they_are_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
