"""Requests said with Persian or Dari inside English (assistant/persian.py), and the turns that came
with them: "You ring him.", "… Dr Weber on video", "Ben, listen, …" said to Ben, and a second request
joined to the one "before that" put first. Plain code, no model; made-up utterances, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.persian import from_persian


@pytest.mark.parametrize(("said", "english"), [
    ("Aval the kitchen, baadan call Clara, lotfan.", "first the kitchen, then call Clara, please."),
    ("Khanum, bathroom zood, merci.", "bathroom quickly, thank you."),
    ("Farda, Anna joon, farda.", "tomorrow, Anna dear, tomorrow."),
    # no word only they have: left as said ("merci", "Alan", "Jan", the Aga)
    ("Merci, Alan and Jan lit the Aga.", "Merci, Alan and Jan lit the Aga."),
])
def test_persian_is_put_in_english(said: str, english: str) -> None:
    assert from_persian(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Agha! Living room. Baleh?", ("Living room",)),
    ("Clara, next door. You ring her.", ("You ring her",)),
    ("Projector on first, and then Anna on video for Maman.", ("Projector on", "Anna on video for Maman")),
    ("Ring Ben. Before that, go to the bedroom and switch the projector off.",
     ("go to the bedroom", "switch the projector off", "Ring Ben")),
    ("Anna, listen, the bathroom tap is broken, you must come and see.", ()),
    ("Ben on the screen looked tired yesterday.", ()),
])
def test_persian_and_its_turns_are_read_as_english_says_them(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).worded_steps == steps
