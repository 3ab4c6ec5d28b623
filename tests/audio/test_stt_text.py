"""Model-free text logic of the STT module."""

from __future__ import annotations

import pytest

from robovoice.audio.stt import _repetition


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
