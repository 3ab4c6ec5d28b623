"""The head tilt of the embedded model on made-up logits (no model needed)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from robovoice.llm.local_head import TOOL_BIAS, HeadTilt

CALL_IDS = [3, 5]  # e.g. "f", "functions"
MESSAGE_IDS = [1, 4]  # e.g. "m", "message"


def logits(at: dict[int, float]) -> Any:
    """Eight token logits, -10 except those given by id."""
    scores = np.full(8, -10.0, dtype=np.single)
    for index, value in at.items():
        scores[index] = value
    return scores


def pick(scores: Any) -> str:
    """Greedy under the head grammar: the best token among those that can start a head."""
    allowed = CALL_IDS + MESSAGE_IDS
    best = max(allowed, key=lambda i: scores[i])
    return "call" if best in CALL_IDS else "message"


def test_the_margin_is_best_call_token_minus_best_message_token() -> None:
    tilt = HeadTilt(CALL_IDS, MESSAGE_IDS, 0.0)
    scores = logits({3: 1.0, 5: 2.5, 1: 0.5, 4: 3.0, 0: 9.0})  # token 0 is outside both heads
    out = tilt([0, 1, 2], scores)
    assert tilt.margin == pytest.approx(-0.5)
    assert np.array_equal(out, scores) and pick(out) == "message"


def test_the_bias_turns_a_near_miss_into_a_call_and_only_moves_call_tokens() -> None:
    scores = logits({5: 2.5, 4: 3.0, 6: 4.0})
    tilt = HeadTilt(CALL_IDS, MESSAGE_IDS, 1.0)
    out = tilt([0], scores.copy())
    assert tilt.margin == pytest.approx(-0.5)  # measured before the bias
    assert pick(out) == "call"
    assert out[5] == pytest.approx(3.5) and out[3] == pytest.approx(-9.0)
    assert out[4] == pytest.approx(3.0) and out[6] == pytest.approx(4.0)  # message and other tokens untouched


def test_a_clear_answer_stays_an_answer() -> None:
    tilt = HeadTilt(CALL_IDS, MESSAGE_IDS, TOOL_BIAS)
    assert pick(tilt([0], logits({5: 0.0, 4: TOOL_BIAS + 0.5}))) == "message"


def test_only_the_first_token_is_tilted() -> None:
    tilt = HeadTilt(CALL_IDS, MESSAGE_IDS, 2.0)
    tilt([0], logits({5: 1.0, 4: 1.5}))
    later = logits({5: 1.0, 4: 1.5})
    assert np.array_equal(tilt([0, 5], later.copy()), later)  # e.g. inside the tool's name
    assert tilt.margin == pytest.approx(-0.5)
