"""Requests said with Spanish inside English (assistant/spanish.py): what the reading makes of them,
and what stays as said."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.spanish import from_spanish


@pytest.mark.parametrize(("said", "english"), [
    ("Órale, kitchen, apúrate!", "kitchen, quickly!"),
    ("Llámalo, he's waiting.", "call him, he's waiting."),
    ("No lo llames todavía.", "don't call him yet."),
    ("Ven a la sala, gracias.", "come to the living room, thank you."),
    ("Pero first the projector.", "but first the projector."),
    ("Mañana, más tarde, ahora no.", "tomorrow, later, not now."),
    # no Spanish request or order word: the rooms stay as said ("sala" is English too)
    ("The sala in that hotel was lovely.", "The sala in that hotel was lovely."),
])
def test_spanish_is_put_in_english(said: str, english: str) -> None:
    assert from_spanish(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Órale, bathroom, rápido.", ("bathroom",)),
    ("Ben, mi hijo... llámalo, please.", ("call him",)),
    ("Hang up, pero before that, ven aquí.", ("come here", "Hang up")),
    ("No vayas a la cocina, it's wet.", ()),
])
def test_spanish_is_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
