"""How the soak judges a command from its events and the robot's state afterwards: a drive the
robot refuses for its battery is right only when the answer says why (a silent "done" or "on
my way" is not), and a spoken stop that lands after the drive arrived stopped nothing."""

from __future__ import annotations

from typing import Any

from robovoice.assistant.events import ToolCalled, ToolReturned
from robovoice.assistant.loop import TurnResult
from robovoice.assistant.metrics import TurnMetrics
from robovoice.sim import SimState
from robovoice.sim.body import Pose
from robovoice.soak.script import STOP_LINE, Command, Outcome, judge
from robovoice.voice.events import PipelineEvent, RobotStopped, UtteranceIgnored, VoiceTurnFinished

KITCHEN = Command("drive", "Hey Jarvis, go to the kitchen.", "navigate_to", place="kitchen")
STOP = Command("stop", "Hey Jarvis, go to the front door.", "navigate_to", follow=STOP_LINE)
LOW_TEXT = "the battery is critically low (3.2 %): the robot only drives to its charging dock"
LOW: dict[str, Any] = {"error": "battery_low", "message": LOW_TEXT, "hint": "tell the user the battery is too low",
                       "details": {"battery_percent": 3.2}}


def _state(place: str, battery: float = 3.2) -> SimState:
    return SimState(pose=Pose(0.0, 0.0, 0.0), nearest_place=place, moving=False, driving_target=None,
                    projector_on=False, call_contact=None, remote_speaking=False, battery_percent=battery,
                    charging=False, max_speed_mps=0.5, collision_avoidance=True)


def _refused_drive(reply: str) -> list[PipelineEvent]:
    called = ToolCalled("c1", "navigate_to", {"target": "kitchen"})
    returned = ToolReturned("c1", "navigate_to", LOW_TEXT, True, 3.0, "battery_low", LOW)
    result = TurnResult(reply, (called,), (returned,), TurnMetrics())
    return [called, returned, VoiceTurnFinished(1, result, cancelled=False)]


def test_a_drive_refused_for_the_battery_is_right_when_the_answer_says_why() -> None:
    outcome = Outcome(KITCHEN, 10.0)
    judge(outcome, _refused_drive("I cannot drive now: my battery is at 3 percent. Shall I go to my dock?"),
          _state("bedroom"))
    assert outcome.done and outcome.answered, outcome.problem
    assert outcome.errors == ["battery_low"] and "battery" in outcome.reply


def test_a_drive_refused_for_the_battery_with_a_silent_answer_is_not_done() -> None:
    outcome = Outcome(KITCHEN, 10.0)
    judge(outcome, _refused_drive("On my way to the kitchen."), _state("bedroom"))
    assert outcome.answered and not outcome.done
    assert outcome.problem == "the drive was refused (battery_low) but the answer does not say why"


def test_a_drive_that_did_not_move_the_robot_is_not_done() -> None:
    called = ToolCalled("c1", "navigate_to", {"target": "kitchen"})
    returned = ToolReturned("c1", "navigate_to", "{}", False, 3.0, None, {"target": "kitchen", "arrived": "kitchen"})
    events: list[PipelineEvent] = [called, returned, VoiceTurnFinished(1, TurnResult(
        "I am at the kitchen now.", (called,), (returned,), TurnMetrics()), cancelled=False)]
    outcome = Outcome(KITCHEN, 10.0)
    judge(outcome, events, _state("bedroom", battery=50.0))
    assert outcome.problem == "the robot is at the bedroom, not the kitchen"


def test_a_stop_after_the_drive_arrived_is_not_done_and_what_was_heard_is_named() -> None:
    called = ToolCalled("c1", "navigate_to", {"target": "front door"})
    arrived = ToolReturned("c1", "navigate_to", "{}", False, 9000.0, None, {"arrived": "front door"})
    late: list[PipelineEvent] = [called, arrived, RobotStopped(True, "stopped", 1.0)]
    outcome = Outcome(STOP, 10.0)
    judge(outcome, late, _state("front door", battery=50.0))
    assert outcome.problem == "the drive arrived: the stop came after it had ended"

    misheard: list[PipelineEvent] = [called, UtteranceIgnored("not_a_stop", 60.4, 62.0, "Stop my rowboat!")]
    outcome = Outcome(STOP, 10.0)
    judge(outcome, misheard, _state("hallway", battery=50.0))
    assert outcome.problem == ("the spoken stop did not reach the robot "
                               "(heard: not_a_stop 'Stop my rowboat!' at 60.4-62.0 s)")


def test_a_stop_that_halted_the_drive_is_done() -> None:
    called = ToolCalled("c1", "navigate_to", {"target": "front door"})
    events: list[PipelineEvent] = [called, RobotStopped(True, "stopped", 1.0)]
    outcome = Outcome(STOP, 10.0)
    judge(outcome, events, _state("hallway", battery=50.0))
    assert outcome.done, outcome.problem


def test_a_stop_whose_drive_never_started_says_so() -> None:
    # at load 24 the model missed its first-token deadline: no drive, so no stop line was said
    outcome = Outcome(STOP, 10.0)
    judge(outcome, [], _state("kitchen", battery=50.0))
    assert outcome.problem == "the drive never started"


def test_a_command_that_came_to_nothing_says_what_was_heard_instead() -> None:
    """A soak's "call Anna" twice ended with no turn at all; the report now says what the
    pipeline heard (the wake word or not, the transcript, an utterance ignored and why)."""
    from robovoice.voice.events import WakeWordHeard

    outcome = Outcome(KITCHEN, 10.0)
    judge(outcome, [], _state("kitchen", battery=50.0))
    assert outcome.problem == "no turn finished with a reply (heard: nothing)"
    outcome = Outcome(KITCHEN, 10.0)
    judge(outcome, [WakeWordHeard(0.8, 12.5, False), UtteranceIgnored("empty", 12.6, 13.0)],
          _state("kitchen", battery=50.0))
    assert outcome.problem == "no turn finished with a reply (heard: wake word at 12.5 s; empty at 12.6-13.0 s)"
