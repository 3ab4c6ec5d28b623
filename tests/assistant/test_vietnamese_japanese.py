"""Requests said with Vietnamese or Japanese inside English (assistant/vietnamese_japanese.py), a "yo"
said after a clause, and "leave it on" after a switch the other way (`neighbours._left_as_is`):
plain code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.vietnamese_japanese import from_vietnamese_japanese


@pytest.mark.parametrize(("said", "english"), [
    ("Không, chưa, later.", "no, not yet, later."),
    ("Go to the kitchen nhé, cảm ơn.", "Go to the kitchen, thank you."),
    ("Ano... onegai, call Ben hayaku.", "please, call Ben quickly."),
    # no word only they have: left as said
    ("Dame Edna was on, oi, and the ano thing.", "Dame Edna was on, oi, and the ano thing."),
])
def test_vietnamese_and_japanese_are_put_in_english(said: str, english: str) -> None:
    assert from_vietnamese_japanese(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Call Clara... ơ, không, not now.", ()),
    ("Bedroom first yo, after that the bathroom.", ("Bedroom first", "the bathroom")),
    ("Switch off the projector. Actually, leave it on.", ()),
    ("Turn the projector off... no wait, leave it alone.", ()),
    ("Leave it on, and go to the hallway.", ("go to the hallway",)),
    # the same way: kept, not taken back ("on" names nothing a "leave" could take back)
    ("Switch the projector on and leave it on.", ("Switch the projector on",)),
    ("Put the projector on. Leave it on please.", ("Put the projector on",)),
])
def test_they_are_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
