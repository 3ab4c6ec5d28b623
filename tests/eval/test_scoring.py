from __future__ import annotations

import json
from pathlib import Path

import pytest

from robovoice.errors import ConfigError
from robovoice.eval.cases import Case, load_cases
from robovoice.eval.scoring import MadeCall, score_case

DATA = Path(__file__).parent.parent / "data" / "eval"


def case(**fields: object) -> Case:
    return Case.model_validate({"id": "c", "text": "x", **fields})


def test_in_order_subset_with_others_between() -> None:
    c = case(expect=[{"tool": "navigate_to", "args": {"target": "kitchen"}}, {"tool": "set_projector_power"}])
    calls = [MadeCall("get_navigation_targets", {}), MadeCall("navigate_to", {"target": " Kitchen "}),
             MadeCall("get_battery_state", {}), MadeCall("set_projector_power", {"on": True})]
    assert score_case(c, calls).passed
    assert not score_case(c, list(reversed(calls))).passed


def test_alternatives_booleans_and_expect_any() -> None:
    c = case(expect=[{"tool": "start_video_call", "args": {"contact": ["Dr. Weber", "Weber"]}}],
             expect_any=[[{"tool": "list_contacts"}]])
    assert score_case(c, [MadeCall("start_video_call", {"contact": "weber"})]).passed
    assert score_case(c, [MadeCall("list_contacts", {})]).passed
    assert not score_case(c, [MadeCall("start_video_call", {"contact": "Anna"})]).passed
    p = case(expect=[{"tool": "set_projector_power", "args": {"on": True}}])
    assert not score_case(p, [MadeCall("set_projector_power", {"on": 1})]).passed
    assert not score_case(p, [MadeCall("set_projector_power", {})]).passed


def test_forbid_and_empty_expect() -> None:
    c = case(expect=[], forbid=["navigate_to"])
    assert score_case(c, []).passed
    verdict = score_case(c, [MadeCall("navigate_to", {"target": "garage"})])
    assert not verdict.passed and "forbidden" in verdict.reason


def test_case_validation(tmp_path: Path) -> None:
    with pytest.raises(ValueError):
        Case.model_validate({"id": "a", "text": "x", "audio": "a.wav"})
    with pytest.raises(ValueError):
        case(setup="flying")
    assert case(setup="projector_on+in_call").setup_states == ("projector_on", "in_call")
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"id": "a", "text": "x"}\n{"id": "b", "text": \n')
    with pytest.raises(ConfigError, match=r"bad.jsonl:2: not valid JSON"):
        load_cases(bad)
    audio = tmp_path / "a.jsonl"
    audio.write_text(json.dumps({"id": "w", "audio": "audio/w.wav", "wake": True}) + "\n")
    assert load_cases(audio)[0].audio == (tmp_path / "audio" / "w.wav").resolve()


def test_shipped_text_set_is_valid_and_covers_every_tool() -> None:
    cases = load_cases(DATA / "text.jsonl")
    assert len(cases) >= 60
    tools = {e.tool for c in cases for cand in c.candidates for e in cand}
    assert tools >= {"navigate_to", "get_navigation_targets", "cancel_navigation", "return_to_dock", "stop_robot",
                     "set_projector_power", "start_video_call", "end_video_call", "list_contacts",
                     "get_battery_state", "get_robot_pose", "get_camera_image"}
    assert sum(1 for c in cases if not c.expect and c.forbid) >= 6  # chit-chat that must not act


def test_resolved_arguments_and_refused_calls() -> None:
    from robovoice.eval.scoring import resolved_arguments

    living = case(expect=[{"tool": "navigate_to", "args": {"target": "living room"}}])
    sent = MadeCall("navigate_to", {"target": "lounge"})
    assert not score_case(living, [sent]).passed
    taken = MadeCall("navigate_to", {"target": "lounge"}, resolved={"target": "living room"})
    assert score_case(living, [taken]).passed
    assert resolved_arguments({"target": "lounge"}, {"target": "living room", "arrived": "living room"}) == {
        "target": "living room"}
    assert resolved_arguments({"target": "Kitchen"}, {"target": "kitchen"}) == {}  # same place, other case
    assert resolved_arguments({"target": "garage"}, {"error": "unknown_target", "details": {"target": "garage"}}) == {}
    assert resolved_arguments({"contact": "my son"}, {"error": "busy", "details": {"contact": "Ben"}}) == {
        "contact": "Ben"}
    assert resolved_arguments({"target": "x"}, None) == {}

    forbid = case(expect=[], forbid=["navigate_to"])
    refused = score_case(forbid, [MadeCall("navigate_to", {"target": "garage"}, error="unknown_target")])
    assert refused.passed and refused.false_actuations == ()
    interrupted = score_case(forbid, [MadeCall("navigate_to", {"target": "kitchen"}, error="cancelled")])
    assert not interrupted.passed and interrupted.false_actuations == ("navigate_to",)  # it drove, then stopped
    looked = score_case(case(expect=[], forbid=["get_robot_pose"]), [MadeCall("get_robot_pose", {}, actuation=False)])
    assert not looked.passed and looked.false_actuations == ()


def test_an_expected_call_the_check_before_acting_refused_never_reached_the_robot() -> None:
    bathroom = case(expect=[{"tool": "navigate_to", "args": {"target": "bathroom"}}])
    gated = MadeCall("navigate_to", {"target": "bathroom"}, error="not_requested")
    verdict = score_case(bathroom, [gated])
    assert not verdict.passed and "not_requested" in verdict.reason
    assert score_case(bathroom, [gated, MadeCall("navigate_to", {"target": "bathroom"})]).passed  # asked again, sent
    # the robot's own refusal did reach it: a drive it found unreachable is the drive that was asked for
    balcony = case(expect=[{"tool": "navigate_to", "args": {"target": "balcony"}}])
    assert score_case(balcony, [MadeCall("navigate_to", {"target": "balcony"}, error="unreachable")]).passed
