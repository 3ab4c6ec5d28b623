"""The completeness rule behind the shorter end-of-turn silence (voice/completeness.py)."""

from __future__ import annotations

import pytest

from robovoice.voice.completeness import is_complete, trails_off, words_of


@pytest.mark.parametrize(
    "text",
    [
        "Go to the kitchen.",
        "turn the projector off",
        "Switch on the projector",
        "What's your battery level?",
        "Where are you?",
        "Call Anna",
        "stop",
        "Stop, please.",
        "The bedroom.",
        "yes",
        "Thank you",
        "drive forward two meters",
        "End the call",
    ],
)
def test_a_whole_request_is_complete(text: str) -> None:
    assert is_complete(text), text


@pytest.mark.parametrize(
    "text",
    [
        "go to the",
        "Go to the",
        "Drive to",
        "turn on the projector and",
        "Turn on the projector, and",
        "um",
        "Go to the kitchen, um",
        "Call my",
        "turn on",
        "switch off",
        "Can you",
        "Where is",
        "Go to the kitchen,",
        "Go to the kitchen...",
        "Go to the kitchen -",
        "",
        "  ",
        "...",
    ],
)
def test_an_unfinished_request_is_not(text: str) -> None:
    assert not is_complete(text), text


def test_words_and_trailing_marks() -> None:
    assert words_of("Let\u2019s GO, to the Kitchen!") == ["let's", "go", "to", "the", "kitchen"]
    assert trails_off("to the kitchen,") and trails_off("and then\u2026") and not trails_off("the kitchen.")
