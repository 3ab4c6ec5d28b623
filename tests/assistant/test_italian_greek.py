"""Requests said with Italian or Greek inside English (assistant/italian_greek.py), and the turns of
English as a second language they bring (assistant/dialects.py): what the reading makes of them."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.italian_greek import from_italian_greek


@pytest.mark.parametrize(("said", "english"), [
    ("Óchi, not now, parakaló.", "no, not now, please."),
    ("Allora, chiama Ben, subito.", "call Ben, right now."),
    ("Ela, efcharistó poli.", "thank you."),
    ("Piano piano, domani.", "slowly, tomorrow."),
    # no word only Italian or Greek has: nothing changed ("ne" is left as said)
    ("Ne, go to the kitchen.", "Ne, go to the kitchen."),
    ("The Ella Fitzgerald record, put it on.", "The Ella Fitzgerald record, put it on."),
])
def test_italian_and_greek_are_put_in_english(said: str, english: str) -> None:
    assert from_italian_greek(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Drive to the bathroom... ochi, hold off, I'm fine.", ()),  # the Greek no takes the drive back
    ("End the call, then to the kitchen you go.", ("End the call", "go to the kitchen")),
    ("Off to the bedroom you go.", ("go to the bedroom",)),
    ("Robot, you finish the call, and after you go to your charger.", ("finish the call", "you go to your charger")),
    ("Grazie mille, robot.", ()),
])
def test_italian_and_greek_are_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
