"""Requests said with Tamil or Malayalam inside English (assistant/tamil_malayalam.py): plain code, no
model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.tamil_malayalam import from_tamil_malayalam


@pytest.mark.parametrize(("said", "english"), [
    ("Bathroom-ku po, kanna.", "go to the bathroom."),
    ("Front door-ilekku po", "go to the front door"),
    ("Ben-ukku oru video call podu.", "video call Ben."),
    ("Projector off pannu, appuram kitchen-ku vaa.", "Projector off, then come to the kitchen."),
    ("Anna, seri, call venda ippo.", "Anna, seri, call no need now."),  # Anna is a contact, never dropped
    # no word only they have: left as said
    ("Call Anna, da", "Call Anna, da"),
    ("The po-faced cat sat there.", "The po-faced cat sat there."),
])
def test_tamil_and_malayalam_are_put_in_english(said: str, english: str) -> None:
    assert from_tamil_malayalam(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Aiyo, so dark. Living room-ku vaa, mole.", ("come to the living room",)),
    ("Clara-kku call pannu, appuram hallway-ku po.", ("call Clara", "go to the hallway")),
    ("Hang up, mone, then sit on the charger.", ("Hang up", "sit on the charger")),  # "mone": the person called
    ("Ben-ku call venda, he is sleeping.", ()),
])
def test_they_are_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
