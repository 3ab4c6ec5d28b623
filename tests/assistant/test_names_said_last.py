"""A name said last after a comma is whom the words are for, and openers, haste and a "can you
show film?" (`neighbours._said_to`, `lexicon`, `hypothetical`): plain code, no model. The
utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.reading import ClauseKind


@pytest.mark.parametrize(("said", "steps"), [
    ("Turn the lamp off and go to the garage, Clara.", ("Turn the lamp off", "go to the garage")),
    ("Go to the garage, then Clara.", ("Go to the garage", "Clara")),  # a list: asked
    ("Go to the garage, Kitchen.", ("Go to the garage", "Kitchen")),  # a room, not a person
    ("Bismillah. The kitchen, then the lounge.", ("The kitchen", "the lounge")),
    ("Lounge, fast, the kettle is boiling!", ("Lounge",)),
])
def test_what_is_asked_beside_a_name_an_opener_or_haste(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


def test_showing_film_is_asked_about_and_putting_the_film_on_is_asked_for() -> None:
    assert read_request("So can you show film with that projector?").clauses[0].kind is ClauseKind.ABILITY
    assert read_request("Could you put the film on the wall?").clauses[0].kind is ClauseKind.REQUEST
    assert read_request("Can you play music?").steps == ()
