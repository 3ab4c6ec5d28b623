"""Requests said in Nigerian or Ghanaian Pidgin (assistant/pidgin.py): what the reading makes of
them, and what stays as said."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.pidgin import from_pidgin
from robovoice.assistant.reading import ClauseKind


@pytest.mark.parametrize(("said", "english"), [
    ("Abeg off the projector, I wan sleep.", "Abeg switch off the projector, I want sleep."),
    ("Ngwa, on that projector.", "switch on that projector."),
    ("Carry yourself go bedroom, my pikin.", "go to the bedroom, my pikin."),
    ("Waka enter bathroom first, then ring Ben for me o.", "go to the bathroom first, then ring Ben for me."),
    ("Kunna the projector, after that go parlour.", "switch on the projector, after that go to the living room."),
    ("Make you go hallway, then come back charger sharp sharp.",
     "go to the hallway, then come back to the charger quickly."),
    ("No go front door o, na rain dey fall.", "don't go to the front door, na rain dey fall."),
    ("Make you no call Clara now, she dey sleep.", "don't call Clara now, she dey sleep."),
    ("Chale, you sabi how to ring Dr. Weber?", "do you know how to ring Dr. Weber?"),
    ("Ben say make we go kitchen tomorrow.", "Ben say let's go to the kitchen tomorrow."),
    ("Biko, off am.", "please, switch off it."),
    ("I beg, on the projector for me.", "please switch on the projector for me."),
    ("I beg your pardon, go to the kitchen.", "I beg your pardon, go to the kitchen."),
    ("End this call, then carry yourself go charge.", "End this call, then go charge."),
    ("Make you go kitchen, from there pass the hallway.", "go to the kitchen, from there go to the hallway."),
    # no Pidgin word: nothing changed ("off", "make you", "no go" are English too)
    ("Off we go to the kitchen, no go-slow.", "Off we go to the kitchen, no go-slow."),
    ("I will make you a cup of tea.", "I will make you a cup of tea."),
    # Hindi and Swahili "chai" (tea) is not Pidgin's "chai!"
    ("Jao kitchen, chai bana do.", "Jao kitchen, chai bana do."),
])
def test_pidgin_requests_are_put_in_english(said: str, english: str) -> None:
    assert from_pidgin(said) == english


@pytest.mark.parametrize(("said", "kinds"), [
    ("Oya end this call, then go and charge.", [ClauseKind.REQUEST, ClauseKind.REQUEST]),
    ("No go front door o, na rain dey fall.", [ClauseKind.NEGATED, ClauseKind.STATEMENT]),
    ("Chale, you sabi how to ring Dr. Weber?", [ClauseKind.ABILITY]),
    ("Call Ben... no, leave am. I go call am myself tomorrow.",
     [ClauseKind.NEGATED, ClauseKind.NEGATED, ClauseKind.NEGATED, ClauseKind.NEGATED]),
])
def test_pidgin_is_read_as_english_says_it(said: str, kinds: list[ClauseKind]) -> None:
    assert [c.kind for c in read_request(said).clauses] == kinds
