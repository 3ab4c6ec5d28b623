"""Node `base`: stop, battery, and the safety RPCs no manifest declares."""

from __future__ import annotations

from typing import Any

import pytest

from robovoice.errors import InvalidArgumentsError
from robovoice.middleware.memory import MemoryMiddleware
from robovoice.sim.base import SAFETY_RPCS

from .sim_testkit import BOUND_S, FeedbackLog, StartRobot


async def test_set_max_speed_changes_how_fast_the_robot_drives(bus: MemoryMiddleware,
                                                               start: StartRobot) -> None:
    robot = await start(nodes=["navigation", "base"])
    result = await bus.call("base", "set_max_speed", {"mps": 1.0}, timeout=1)
    assert result == {"max_speed_mps": 1.0, "previous_mps": 0.5}
    assert robot.state.max_speed_mps == 1.0
    drive = await bus.run_action("navigation", "drive_to", {"target": "kitchen"}, on_feedback=FeedbackLog(),
                                 timeout=BOUND_S)
    assert drive["duration_s"] == pytest.approx(drive["distance_m"] / 1.0, rel=0.3)  # not / 0.5
    with pytest.raises(InvalidArgumentsError):
        await bus.call("base", "set_max_speed", {"mps": 5.0}, timeout=1)
    with pytest.raises(InvalidArgumentsError):
        await bus.call("base", "set_max_speed", {"mps": "fast"}, timeout=1)
    assert robot.state.max_speed_mps == 1.0


async def test_collision_avoidance_can_be_switched_off_and_on(bus: MemoryMiddleware,
                                                              start: StartRobot) -> None:
    robot = await start(nodes=["base"])
    assert robot.state.collision_avoidance is True
    off = await bus.call("base", "disable_collision_avoidance", {}, timeout=1)
    assert off == {"collision_avoidance": False}
    assert robot.state.collision_avoidance is False
    status = await bus.call("base", "get_status", {}, timeout=1)
    assert status["collision_avoidance"] is False and status["max_speed_mps"] == 0.5
    on = await bus.call("base", "enable_collision_avoidance", {}, timeout=1)
    assert on == {"collision_avoidance": True}
    assert robot.state.collision_avoidance is True


async def test_safety_rpcs_are_offered_on_the_middleware_but_in_no_manifest(
    bus: MemoryMiddleware, start: StartRobot
) -> None:
    await start()
    nodes = bus.nodes()
    offered = {r.name for r in nodes["base"].rpcs}
    assert {"set_max_speed", "disable_collision_avoidance"} <= set(SAFETY_RPCS) <= offered
    for info in nodes.values():
        assert info.manifest is not None
        referenced = {tool["rpc"] for tool in info.manifest.get("tools", [])}
        assert referenced.isdisjoint(SAFETY_RPCS), info.name
        text = str(info.manifest)
        for rpc in SAFETY_RPCS:
            assert rpc not in text


async def test_battery_drains_while_driving_and_charges_on_the_dock(
    bus: MemoryMiddleware, start: StartRobot, make_inbox: Any
) -> None:
    robot = await start(nodes=["navigation", "base"])
    battery = await make_inbox("battery", robot.clock)
    first = (await battery.wait_count(1))[0].value
    assert set(first) == {"percent", "charging", "voltage"}
    assert first["charging"] is True  # it starts on its dock
    await bus.call("base", "set_battery_percent", {"percent": 50}, timeout=1)
    await battery.wait_for(lambda items: items[-1].value["percent"] > 50.0)  # charging
    await bus.run_action("navigation", "drive_to", {"target": "front door"}, on_feedback=FeedbackLog(),
                         timeout=BOUND_S)
    at_door = robot.state.battery_percent
    assert at_door < 51.0 and not robot.state.charging
    count = len(battery.items)
    await battery.wait_count(count + 1)
    assert battery.items[-1].value["charging"] is False
    assert battery.items[-1].value["percent"] <= at_door
    assert 21.0 < battery.items[-1].value["voltage"] < 25.2
