"""Nepali said inside English (assistant/nepali.py): plain code, no model. The utterances are made
up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.nepali import from_nepali


@pytest.mark.parametrize(("said", "english"), [
    ("Off gara, please.", "switch it off, please."),
    ("Projector on gara.", "switch the Projector on."),
    ("Kitchen tira jaau ta.", "go to Kitchen."),
    ("Bedroom ma aaija na.", "come to Bedroom."),
    ("Clara lai phone gara.", "call Clara."),
    ("Dr. Weber lai video call gardinus.", "call Dr. Weber."),
    ("Ahile hoina, bholi.", "not now, tomorrow."),
    ("Hajur, go to the hallway ani call Ben.", "go to the hallway and then call Ben."),
    # English as it is: no word only Nepali has
    ("Ma is in the kitchen.", "Ma is in the kitchen."),
    ("Ta very much.", "Ta very much."),
    ("I will call Ani later.", "I will call Ani later."),
])
def test_nepali_is_put_in_english(said: str, english: str) -> None:
    assert from_nepali(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Hunchha, hang up now, ani go back to your charger.", ("hang up now", "go back to your charger")),
    ("Hallway tira jaau, ani Anna lai phone gara.", ("go to Hallway", "call Anna")),
    ("Ahile hoina, bholi call Ben.", ()),
])
def test_it_is_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
