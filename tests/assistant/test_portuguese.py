"""Requests said with Portuguese inside English (assistant/portuguese.py): what the reading makes of
them, and what stays as said. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.portuguese import from_portuguese


@pytest.mark.parametrize(("said", "english"), [
    ("Liga pra Clara, por favor.", "call Clara, please."),
    ("Liga o projector, querida.", "turn on the projector, dear."),
    ("Olha, vai pra cozinha agora, tá?", "go to the kitchen now?"),
    ("Não liga pro Ben ainda não.", "don't call Ben not yet."),
    ("Primeiro desliga o projetor, e depois vem cá.", "first turn off the projector, and then come here."),
    # no word only Portuguese has: left as said ("sala", "pro", "porta" are English too)
    ("The sala at the pro shop had a porta cabin.", "The sala at the pro shop had a porta cabin."),
    ("Nao, come here.", "Nao, come here."),  # a Japanese name, not "não"
])
def test_portuguese_is_put_in_english(said: str, english: str) -> None:
    assert from_portuguese(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Vai pro banheiro, rapidinho.", ("go to the bathroom",)),
    ("Liga pra minha filha, né.", ("call my daughter",)),
    ("Não vai pra sala, the floor is wet.", ()),
    ("Amanhã you can liga pro Ben.", ()),
])
def test_portuguese_is_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


def test_a_place_after_what_a_step_is_for_goes_on_from_it() -> None:
    said = "Go to the kitchen, to check the oven, then the hallway, and then ring Anna."
    assert len(read_request(said).steps) == 3
