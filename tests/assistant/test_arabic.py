"""Requests said with Arabic inside English (assistant/arabic.py), and a place said after "now"
(assistant/clause_kind.py): what the reading makes of them."""

from __future__ import annotations

import pytest

from robovoice.assistant.arabic import from_arabic
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "english"), [
    ("Yalla, ring Ben, min fadlik.", "ring Ben, please."),
    ("The kitchen, yalla!", "The kitchen, quickly!"),
    ("Shukran kteer, ya habibti.", "thank you."),
    ("Yalla, kitchen, habibti.", "go to kitchen."),  # (text test v131)
    ("Inshallah you can ring Clara now.", "you can ring Clara now."),
    ("Switch the projector off, khalas.", "Switch the projector off."),
    ("Khalas, stop!", "enough, stop!"),
    ("Hallway, ya Jarvis.", "Hallway, Jarvis."),
    ("Bukra, ba'dain, halla2.", "tomorrow, later, now."),
    ("Khalas!", "enough!"),
    # inshallah is left as said, and nothing changes where no word only Arabic has was said
    ("Call Anna tomorrow, inshallah.", "Call Anna tomorrow, inshallah."),
    ("Ya know what, the kitchen is lovely.", "Ya know what, the kitchen is lovely."),
])
def test_arabic_is_put_in_english(said: str, english: str) -> None:
    assert from_arabic(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Into the kitchen, yalla.", ("Into the kitchen",)),
    ("Now the hallway, and after, the front door.", ("Now the hallway", "the front door")),
    ("Bukra inshallah, not now.", ()),
    ("Now my knees hurt.", ()),  # "now" and a sentence: talk
    ("Now then, the living room is a mess.", ()),
])
def test_arabic_is_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
