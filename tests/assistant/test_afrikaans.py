"""Requests said with Afrikaans or isiZulu inside South African English (assistant/afrikaans.py):
what the reading makes of them, and what stays as said."""

from __future__ import annotations

import pytest

from robovoice.assistant.afrikaans import from_afrikaans
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "english"), [
    ("Gaan gou na die bedroom and ring Ben from there.", "go to the bedroom and ring Ben from there."),
    ("Kom na die sitkamer, asseblief.", "come to the living room, please."),
    ("Skakel die projector aan vir my.", "switch the projector on for me."),
    ("Ag, sit die projector af.", "switch the projector off."),
    ("Bel my dogter Anna, dankie.", "call my daughter Anna, thank you."),
    ("Ngiyacela, hamba to the kombuis.", "please, go to the kitchen."),
    ("Moenie vir Clara bel nie, sy slaap.", "don't Clara bel, sy slaap."),
    ("Bel vir Ben, asseblief.", "call Ben, please."),
    ("Nie nou nie, Oupa.", "not now, Oupa."),
    # no word only Afrikaans or isiZulu has: nothing changed ("die", "loop", "Bel" the name)
    ("Call Bel for me.", "Call Bel for me."),
    ("Don't let the battery die, go round the loop to the dock.",
     "Don't let the battery die, go round the loop to the dock."),
])
def test_afrikaans_and_zulu_are_put_in_english(said: str, english: str) -> None:
    assert from_afrikaans(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Ry na die kombuis en dan bel Clara.", ("go to the kitchen", "call Clara")),
    ("Moenie na die voordeur gaan nie.", ()),
    ("Eish, nog nie, Gogo is sleeping.", ()),
])
def test_afrikaans_is_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
