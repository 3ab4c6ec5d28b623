"""Requests said with French inside English, as in Quebec (assistant/french.py): what the reading
makes of them, and what stays as said."""

from __future__ import annotations

import pytest

from robovoice.assistant.french import from_french
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "english"), [
    ("Éteins le projecteur, s'il te plaît.", "turn off the projector, please."),
    ("Va dans la chambre, pis appelle mon fils.", "go to the bedroom, then call my son."),
    ("Raccroche avec Clara et après va à la cuisine.", "hang up avec Clara and then go to the kitchen."),
    ("D'abord, viens au salon.", "first, go to the living room."),
    ("Appelle-la pas, elle dort.", "don't call, elle dort."),
    ("Pas maintenant, plus tard.", "not now, later."),
    # no word only French has: nothing changed ("ferme", "salon", "base" are English too)
    ("The salon down the road does a nice perm.", "The salon down the road does a nice perm."),
    ("Ferme the gate on your way out, Ben said.", "Ferme the gate on your way out, Ben said."),
])
def test_french_is_put_in_english(said: str, english: str) -> None:
    assert from_french(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Allume le projecteur, I want to see the photos.", ("turn on the projector",)),
    ("Va à la porte d'en avant, the front door, pis appelle Anna.", ("go to the front door", "call Anna")),
    ("Appelle pas le docteur, c'est correct.", ()),
])
def test_french_is_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
