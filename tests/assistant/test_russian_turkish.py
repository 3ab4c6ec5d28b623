"""Requests said with Russian or Turkish inside English (assistant/russian_turkish.py), and the turns
of English they come with ("Kitchen I said", "and last you call Ben", "Close call, …"): what the
reading makes of them, and what stays as said. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.russian_turkish import from_russian_turkish


@pytest.mark.parametrize(("said", "english"), [
    ("Davai, kitchen, pozhaluysta.", "kitchen, please."),
    ("Tamam, sonra call Ben, sağol.", "then call Ben, thank you."),
    ("Nyet, not the bedroom, k\u0131z\u0131m.", "no, not the bedroom, dear."),
    ("Yar\u0131n you can go to the hallway.", "tomorrow you can go to the hallway."),
    # no word only they have: left as said ("once", "tak" and "nu" alone)
    ("Once you're in the kitchen, ring Ben.", "Once you're in the kitchen, ring Ben."),
    ("Nu, that's a new one.", "Nu, that's a new one."),
])
def test_russian_and_turkish_are_put_in_english(said: str, english: str) -> None:
    assert from_russian_turkish(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("Hadi, bathroom. Quick quick.", ("bathroom",)),
    ("Nyet! Not there. Living room I said, living room.", ("Living room",)),
    ("First the hallway, then the projector on, and last you ring Clara.", 3),
    ("Bye-bye Anna. Close call, then go charge.", ("end the call", "go charge")),
    ("Yar\u0131n, lütfen, go to the bedroom.", ()),
])
def test_russian_and_turkish_are_read_as_english_says_it(said: str, steps: tuple[str, ...] | int) -> None:
    read = read_request(said).steps
    assert (len(read) if isinstance(steps, int) else read) == steps


def test_a_close_call_said_of_what_happened_ends_nothing() -> None:
    assert not read_request("Phew, that was a close call on the stairs.").asks_action
