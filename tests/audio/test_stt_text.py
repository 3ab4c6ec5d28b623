"""Model-free text logic of the STT module."""

from __future__ import annotations

import pytest

from robovoice.audio.stt import _repetition, strip_wake_phrase


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("Hey, Jarvis, turn on the projector.", "turn on the projector."),
        ("hey jarvis. Go to the kitchen", "Go to the kitchen"),
        ("Jarvis, stop.", "stop."),
        ("Turn on the Jarvis mode", "Turn on the Jarvis mode"),
        ("Hey Jarvis", ""),
    ],
)
def test_strip_wake_phrase(text: str, expected: str) -> None:
    assert strip_wake_phrase(text) == expected


@pytest.mark.parametrize(
    ("ids", "drop"),
    [
        ([1, 2, 3], 0),
        ([7, 7], 0),
        ([7, 7, 7], 2),
        ([1, 2, 3, 4, 5, 4, 5, 4, 5], 4),
        ([1, 2, 3, 1, 2, 3, 1, 2], 0),
        ([9, 1, 2, 3, 4, 1, 2, 3, 4], 4),
        ([9, 8, 1, 2, 3, 4, 5, 6, 1, 2, 3, 4, 5, 6], 6),
        ([1, 2, 3, 4, 5, 6, 7, 8], 0),
    ],
)
def test_moonshine_repetition_guard(ids: list[int], drop: int) -> None:
    assert _repetition(ids) == drop
