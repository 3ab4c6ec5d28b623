"""Node `navigation`: drives with feedback, checks before moving, cancellation."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from robovoice.errors import CancelledByRobotError, InvalidArgumentsError, RobotFailure
from robovoice.middleware.memory import MemoryMiddleware
from robovoice.sim.world import place

from .sim_testkit import BOUND_S, FeedbackLog, StartRobot

KNOWN = ["kitchen", "living room", "bedroom", "bathroom", "hallway", "front door", "charging dock"]


async def _drive(bus: MemoryMiddleware, target: str, feedback: FeedbackLog) -> Any:
    return await bus.run_action("navigation", "drive_to", {"target": target}, on_feedback=feedback,
                                timeout=BOUND_S)


async def test_drive_reaches_the_target_with_feedback(
    bus: MemoryMiddleware, start: StartRobot, feedback: FeedbackLog, make_inbox: Any
) -> None:
    robot = await start(speed=10)  # feedback rates are checked: not too fast for a loaded machine
    poses = await make_inbox("pose", robot.clock)
    battery_before = robot.state.battery_percent
    sim_start = robot.clock.now()

    result = await _drive(bus, "the Kitchen", feedback)

    sim_elapsed = robot.clock.now() - sim_start
    assert result["arrived"] == "kitchen"
    assert result["distance_m"] == pytest.approx(0.8 + 2.0 + 2.5)  # dock -> hallway -> kitchen
    assert result["duration_s"] == pytest.approx(result["distance_m"] / 0.5, rel=0.3)
    assert sim_elapsed >= result["distance_m"] / 0.5
    # feedback: at least 2 Hz sim time, progress monotone up to the total, readable messages
    items = feedback.items
    assert len(items) >= 2 * result["duration_s"]
    progress = [f.progress for f in items]
    assert progress == sorted(progress)
    assert progress[0] == 0 and progress[-1] == pytest.approx(items[-1].total)
    assert all(f.total == pytest.approx(result["distance_m"]) for f in items)
    assert items[0].message == "5 m to the kitchen"
    assert items[-1].message == "arrived at the kitchen"
    # the pose moved from the dock to the kitchen, through the hallway, and stopped moving
    state = robot.state
    kitchen = place("kitchen").position
    assert (state.pose.x, state.pose.y) == pytest.approx((kitchen.x, kitchen.y))
    assert state.nearest_place == "kitchen" and not state.moving and state.driving_target is None
    assert any(p["moving"] for p in poses.values)
    assert any(p["y"] == pytest.approx(4.0) for p in poses.values)
    # the battery paid for it
    assert state.battery_percent < battery_before


async def test_already_there_is_a_success(bus: MemoryMiddleware, start: StartRobot,
                                          feedback: FeedbackLog) -> None:
    await start(nodes=["navigation"])
    result = await _drive(bus, "dock", feedback)
    assert result["arrived"] == "charging dock"
    assert result["already_there"] is True and result["distance_m"] == 0


async def test_unknown_target(bus: MemoryMiddleware, start: StartRobot, feedback: FeedbackLog) -> None:
    robot = await start(nodes=["navigation"])
    with pytest.raises(RobotFailure) as err:
        await _drive(bus, "garage", feedback)
    body = err.value.to_dict()
    assert body["error"] == "unknown_target"
    assert body["hint"] == "tell the user you do not know that place, name the known places and ask which one they mean"
    assert body["details"]["known_places"] == KNOWN
    assert "garage" in body["message"]
    assert not robot.state.moving and feedback.items == []


async def test_balcony_is_unreachable(bus: MemoryMiddleware, start: StartRobot,
                                      feedback: FeedbackLog) -> None:
    robot = await start(nodes=["navigation"])
    with pytest.raises(RobotFailure) as err:
        await _drive(bus, "Balcony", feedback)
    assert err.value.code == "unreachable"
    assert "door is closed" in err.value.message
    assert err.value.details == {"target": "balcony", "reason": "the balcony door is closed"}
    assert err.value.hint
    assert not robot.state.moving and feedback.items == []


async def test_bad_arguments(bus: MemoryMiddleware, start: StartRobot, feedback: FeedbackLog) -> None:
    await start(nodes=["navigation"])
    for args in ({}, {"target": ""}, {"target": 3}, {"target": "kitchen", "speed": 2}):
        with pytest.raises(InvalidArgumentsError):
            await bus.run_action("navigation", "drive_to", args, on_feedback=feedback, timeout=BOUND_S)


async def test_low_battery_refuses_except_to_the_dock(
    bus: MemoryMiddleware, start: StartRobot, feedback: FeedbackLog
) -> None:
    robot = await start(nodes=["navigation", "base"])
    await bus.call("base", "set_battery_percent", {"percent": 3}, timeout=1)
    with pytest.raises(RobotFailure) as err:
        await _drive(bus, "kitchen", feedback)
    assert err.value.code == "battery_low"
    assert err.value.details["battery_percent"] == 3
    assert "charging dock" in (err.value.hint or "")
    assert not robot.state.moving
    # ... but the way home is allowed (here: already there)
    assert (await _drive(bus, "charging dock", feedback))["arrived"] == "charging dock"
    await bus.call("base", "set_battery_percent", {"percent": 0.5}, timeout=1)
    with pytest.raises(RobotFailure) as err:
        await _drive(bus, "charging dock", feedback)
    assert err.value.code == "battery_empty"


async def _start_drive(bus: MemoryMiddleware, target: str, feedback: FeedbackLog,
                       metres: float = 1.0) -> asyncio.Task[Any]:
    task = asyncio.create_task(_drive(bus, target, feedback))
    await feedback.wait_for(lambda items: bool(items) and items[-1].progress >= metres)
    return task


async def test_cancel_mid_drive(bus: MemoryMiddleware, start: StartRobot, feedback: FeedbackLog) -> None:
    robot = await start(nodes=["navigation"])
    task = await _start_drive(bus, "front door", feedback)
    assert robot.state.driving_target == "front door" and robot.state.moving
    status = await bus.call("navigation", "get_status", {}, timeout=1)
    assert status["driving"] is True and status["target"] == "front door"

    result = await bus.call("navigation", "cancel", {}, timeout=1)

    assert result["cancelled"] is True and result["target"] == "front door"
    with pytest.raises(CancelledByRobotError) as err:
        await task
    assert err.value.code == "cancelled"
    assert err.value.details["target"] == "front door"
    assert 1.0 <= err.value.details["distance_done_m"] < 8.0
    state = robot.state
    assert not state.moving and state.driving_target is None
    pose_after = state.pose
    # nothing to cancel now
    with pytest.raises(RobotFailure) as nothing:
        await bus.call("navigation", "cancel", {}, timeout=1)
    assert nothing.value.code == "not_driving"
    assert robot.state.pose == pose_after  # it stays where it stopped
    # and it can drive on from the middle of nowhere
    assert (await _drive(bus, "bedroom", FeedbackLog()))["arrived"] == "bedroom"


async def test_base_stop_cancels_the_drive(bus: MemoryMiddleware, start: StartRobot,
                                           feedback: FeedbackLog) -> None:
    robot = await start(nodes=["navigation", "base"])
    task = await _start_drive(bus, "living room", feedback)
    result = await bus.call("base", "stop", {}, timeout=1)
    assert result == {"stopped": True, "was_moving": True, "interrupted": "drive to the living room"}
    with pytest.raises(CancelledByRobotError) as err:
        await task
    assert "stop" in err.value.details["reason"]
    assert not robot.state.moving
    # stop with nothing moving still succeeds
    assert await bus.call("base", "stop", {}, timeout=1) == {"stopped": True, "was_moving": False,
                                                             "interrupted": None}


async def test_cancelling_the_caller_stops_the_robot(bus: MemoryMiddleware, start: StartRobot,
                                                     feedback: FeedbackLog) -> None:
    robot = await start(nodes=["navigation"])
    task = await _start_drive(bus, "front door", feedback)
    task.cancel()
    with pytest.raises(asyncio.CancelledError):
        await task
    assert not robot.state.moving and robot.state.driving_target is None
    pose = robot.state.pose
    with pytest.raises(RobotFailure, match="not driving"):
        await bus.call("navigation", "cancel", {}, timeout=1)
    assert robot.state.pose == pose


async def test_a_new_goal_replaces_the_drive(bus: MemoryMiddleware, start: StartRobot,
                                             feedback: FeedbackLog) -> None:
    robot = await start(nodes=["navigation"])
    first = await _start_drive(bus, "front door", feedback)
    second = await _drive(bus, "kitchen", FeedbackLog())
    assert second["arrived"] == "kitchen"
    with pytest.raises(CancelledByRobotError, match="replaced"):
        await first
    assert robot.state.nearest_place == "kitchen"


async def test_list_targets_and_status(bus: MemoryMiddleware, start: StartRobot) -> None:
    await start(nodes=["navigation"])
    targets = await bus.call("navigation", "list_targets", {}, timeout=1)
    assert targets == {"places": KNOWN, "unreachable": {"balcony": "the balcony door is closed"},
                       "nearest_place": "charging dock"}
    status = await bus.call("navigation", "get_status", {}, timeout=1)
    assert status["driving"] is False and status["target"] is None
