"""Haitian and French-Antillean Creole said inside English (assistant/creole.py): plain code, no
model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.creole import from_creole
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "english"), [
    ("Eske you can put Ben on the screen?", "you can put Ben on the screen?"),
    ("Switch the projector on épi come to the bedroom, chéri.",
     "Switch the projector on and then come to the bedroom."),
    ("Rele Clara tanpri.", "call Clara please."),
    ("Pa call Anna kounye a.", "don't call Anna now."),
    ("Me I ka cook, doudou.", "Me I cook."),
    ("Bondye, where is my stick?", "where is my stick?"),
    ("Robot la, go to the hallway, mèsi.", "Robot, go to the hallway, thank you."),
    # English (and French) as it is: no word only Creole has
    ("The call la, hang it up.", "The call la, hang it up."),
    ("La cocina, please.", "La cocina, please."),
    ("I like Paris, the food is good.", "I like Paris, the food is good."),
])
def test_creole_is_put_in_english(said: str, english: str) -> None:
    assert from_creole(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Eske you could ring Clara? She is waiting.", ("you could ring Clara",)),
    ("Projector la, turn it off, épi go charge yourself.", ("turn it off", "go charge yourself")),
    ("Robot la, tanpri, go in the bedroom for me.", ("go in the bedroom for me",)),
    ("Come in the kitchen with me, doudou.", ("Come in the kitchen with me",)),
])
def test_it_is_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
