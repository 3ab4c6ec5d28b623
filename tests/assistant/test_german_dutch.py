"""Requests said with German or Dutch inside English (assistant/german_dutch.py): what the reading
makes of them, and what stays as said."""

from __future__ import annotations

import pytest

from robovoice.assistant.german_dutch import from_german_dutch
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "english"), [
    ("Beamer aus, bitte.", "the projector off, please."),
    ("Switch the beamer out.", "Switch the projector off."),
    ("Ring then Clara, danke schön.", "then ring Clara, thank you."),
    ("Genau, morgen, not jetzt.", "tomorrow, not now."),
    ("Nee, dank je wel.", "no, thank you."),
    # no word only German or Dutch has: nothing changed ("also", "nu", "out" alone are left)
    ("Also, go out to the hallway.", "Also, go out to the hallway."),
    ("Nu, bine, not necessary.", "Nu, bine, not necessary."),
])
def test_german_and_dutch_are_put_in_english(said: str, english: str) -> None:
    assert from_german_dutch(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Beamer out, bitte.", ("the projector off",)),
    ("End with Clara and ring then Ben.", ("End with Clara", "ring Ben")),
    ("Nein, morgen.", ()),
])
def test_german_and_dutch_are_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
