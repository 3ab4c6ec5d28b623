"""Per-turn latency marks and their p50/p95 summary over many turns (no models, a fake clock)."""

from __future__ import annotations

import pytest

from robovoice.assistant.metrics import TurnMetrics, percentile, summarise


def test_percentile_interpolates_between_ranks_like_numpy() -> None:
    values = [40.0, 10.0, 30.0, 20.0]  # order does not matter
    assert percentile(values, 50) == pytest.approx(25.0)
    assert percentile(values, 95) == pytest.approx(38.5)  # 30 + 0.85 x (40 - 30)
    assert (percentile(values, 0), percentile(values, 100)) == (10.0, 40.0)
    assert percentile([7.0], 95) == 7.0  # one turn: every percentile is that turn
    with pytest.raises(ValueError, match="no values"):
        percentile([], 50)
    with pytest.raises(ValueError, match=r"0\.\.100"):
        percentile(values, 101)


def test_summarise_gives_p50_p95_and_count_per_stage() -> None:
    turns = [
        {"transcript": 100.0, "first_token": 300.0, "finished": 900.0, "model_ms": 500.0},
        {"transcript": 120.0, "first_token": 280.0, "finished": 1100.0, "model_ms": 700.0},
        {"transcript": 80.0, "finished": 700.0, "model_ms": 400.0},  # no first token: skipped there
    ]
    summary = summarise(turns)
    assert list(summary) == ["finished", "first_token", "model_ms", "transcript"]  # sorted by stage
    assert summary["transcript"] == {"p50": 100.0, "p95": 118.0, "n": 3}
    assert summary["first_token"] == {"p50": 290.0, "p95": 299.0, "n": 2}
    assert summary["finished"] == {"p50": 900.0, "p95": 1080.0, "n": 3}


def test_summarise_pools_tool_stages_over_tool_names_and_rounds() -> None:
    turns = [
        {"tool_call:navigate_to": 400.04, "tool_result:navigate_to": 2400.0},
        {"tool_call:get_robot_pose": 350.0, "tool_result:get_robot_pose": 380.0},
    ]
    summary = summarise(turns)
    assert set(summary) == {"tool_call", "tool_result"}
    assert summary["tool_call"] == {"p50": 375.0, "p95": 397.5, "n": 2}
    assert summary["tool_result"]["n"] == 2
    assert summarise([]) == {}


def test_turn_metrics_feed_summarise() -> None:
    now = [10.0]
    turns = []
    for first_token_s in (0.2, 0.4):
        metrics = TurnMetrics(clock=lambda: now[0])
        now[0] += first_token_s
        metrics.mark("first_token")
        metrics.mark("first_token", at=now[0] + 5)  # a stage is marked once: the later mark is ignored
        metrics.model_ms = first_token_s * 1000
        turns.append(metrics.as_dict())
    assert turns[0] == {"first_token": 200.0, "model_ms": 200.0, "tools_ms": 0.0}
    summary = summarise(turns)
    assert summary["first_token"] == {"p50": 300.0, "p95": 390.0, "n": 2}
