"""`SimRobot`: start, state, setups, stop; topic rates in sim time."""

from __future__ import annotations

import asyncio
import base64
from collections.abc import Mapping
from typing import Any

import pytest

from robovoice.errors import ConfigError, NodeUnavailableError
from robovoice.middleware.base import ActionHandler, NodeHost, NodeInfo, RpcHandler
from robovoice.middleware.memory import MemoryMiddleware
from robovoice.sim import NODE_NAMES, SETUP_NAMES, SimRobot, run_sim_forever, start_sim_robot
from robovoice.sim.robot import SETUP_CRAWL_MPS

from .sim_testkit import BOUND_S, FeedbackLog, StartRobot


async def test_all_nodes_or_the_named_ones(bus: MemoryMiddleware, start: StartRobot) -> None:
    robot = await start(nodes=["projector", "base"])
    assert sorted(bus.nodes()) == ["base", "projector"]
    assert robot.node_names == ("projector", "base")
    with pytest.raises(ConfigError, match="garage"):
        await start_sim_robot(bus, nodes=["garage"])
    assert NODE_NAMES == ("navigation", "base", "localization", "camera", "projector", "communication")


async def test_stop_withdraws_every_node(bus: MemoryMiddleware) -> None:
    robot = await start_sim_robot(bus, speed=40)
    assert sorted(bus.nodes()) == sorted(NODE_NAMES)
    await robot.apply_setup("driving")
    await robot.stop()
    await robot.stop()  # idempotent
    assert bus.nodes() == {}
    assert robot.failure is None
    assert not robot.state.moving
    with pytest.raises(NodeUnavailableError):
        await bus.call("projector", "get_state", {}, timeout=1)
    await asyncio.wait_for(robot.wait(), BOUND_S)  # returns once stopped


async def test_initial_state(start: StartRobot) -> None:
    state = (await start()).state
    assert state.nearest_place == "charging dock" and state.charging
    assert not state.moving and state.driving_target is None
    assert not state.projector_on and state.call_contact is None and not state.in_call
    assert state.max_speed_mps == 0.5 and state.collision_avoidance
    assert 0 < state.battery_percent <= 100


async def test_setups(bus: MemoryMiddleware, start: StartRobot) -> None:
    robot = await start()
    assert SETUP_NAMES == ("driving", "in_call", "projector_on")
    await robot.apply_setup("driving+in_call")
    state = robot.state
    assert state.moving and state.driving_target == "front door"  # the farthest from the dock
    assert state.call_contact == "Anna" and not state.projector_on
    status = await bus.call("navigation", "get_status", {}, timeout=1)
    assert status["driving"] is True
    await robot.apply_setup("projector_on+in_call")  # applying again is harmless
    assert robot.state.projector_on and robot.state.call_contact == "Anna"
    # the drive set up is a real one: cancelling it through the RPC ends it
    result = await bus.call("navigation", "cancel", {}, timeout=1)
    assert result["target"] == "front door"
    assert not robot.state.moving
    await robot.reset()
    state = robot.state
    assert not state.moving and not state.projector_on and state.call_contact is None
    await robot.apply_setup("")
    await robot.apply_setup("none")
    assert robot.state == state


async def test_setup_drive_crawls_until_a_drive_is_asked_for(bus: MemoryMiddleware) -> None:
    # at 40x a drive at cruise speed reaches the farthest place in well under a second; the setup
    # drive must still be under way when a slow model answers, and a real request drives at cruise
    robot = await start_sim_robot(bus, speed=40)
    try:
        await robot.apply_setup("driving")
        assert robot.state.max_speed_mps == SETUP_CRAWL_MPS
        await asyncio.sleep(1.0)
        assert robot.state.moving and robot.state.driving_target == "front door"
        feedback = FeedbackLog()
        asked = asyncio.create_task(bus.run_action("navigation", "drive_to", {"target": "kitchen"},
                                                   on_feedback=feedback, timeout=BOUND_S))
        await feedback.wait_for(bool)  # under way; the preempted setup drive's end gives the speed back
        for _ in range(100):
            if robot.state.max_speed_mps != SETUP_CRAWL_MPS:
                break
            await asyncio.sleep(0.02)
        assert robot.state.driving_target == "kitchen" and robot.state.max_speed_mps == 0.5
        result = await asyncio.wait_for(asked, BOUND_S)
        assert result["target"] == "kitchen"
        await robot.apply_setup("driving")
        await bus.call("base", "set_max_speed", {"mps": 0.3}, timeout=1)  # a change made meanwhile stays
        await robot.reset()
        assert robot.state.max_speed_mps == 0.3
    finally:
        await robot.stop()


async def test_setup_in_call_replaces_another_call(bus: MemoryMiddleware, start: StartRobot) -> None:
    robot = await start(nodes=["communication"])
    await bus.call("communication", "start_call", {"contact": "Ben"}, timeout=1)
    await robot.apply_setup("in_call")
    assert robot.state.call_contact == "Anna"


async def test_unknown_setup(start: StartRobot) -> None:
    robot = await start(nodes=["projector"])
    with pytest.raises(ConfigError, match="flying") as err:
        await robot.apply_setup("projector_on+flying")
    assert "driving, in_call, projector_on" in str(err.value)
    assert not robot.state.projector_on  # nothing applied


async def test_run_sim_forever_until_cancelled(bus: MemoryMiddleware) -> None:
    ready: list[SimRobot] = []
    is_ready = asyncio.Event()

    def on_ready(robot: SimRobot) -> None:
        ready.append(robot)
        is_ready.set()

    task = asyncio.create_task(run_sim_forever(bus, speed=40, nodes=["projector", "navigation"],
                                               setup="projector_on", on_ready=on_ready))
    await asyncio.wait_for(is_ready.wait(), BOUND_S)
    assert sorted(bus.nodes()) == ["navigation", "projector"]
    assert await bus.call("projector", "get_state", {}, timeout=1) == {"on": True}
    assert ready[0].state.projector_on
    task.cancel()
    with pytest.raises(asyncio.CancelledError):
        await task
    assert bus.nodes() == {}


def _rate(stamps: list[float]) -> float:
    return (len(stamps) - 1) / (stamps[-1] - stamps[0])


@pytest.mark.parametrize(
    ("node", "topic", "hz", "speed"),  # speeds keep real periods >= 25 ms: robust on a loaded machine
    [("localization", "pose", 10.0, 4), ("base", "battery", 1.0, 20), ("camera", "camera", 3.0, 12),
     ("communication", "call_state", 1.0, 20)],
)
async def test_topic_rates_in_sim_time(start: StartRobot, make_inbox: Any, node: str, topic: str,
                                       hz: float, speed: float) -> None:
    robot = await start(nodes=[node], speed=speed)
    box = await make_inbox(topic, robot.clock)
    received = await box.wait_count(16)
    rate = _rate([item.sim_time for item in received])
    assert rate == pytest.approx(hz, rel=0.25)


async def test_topic_payloads(start: StartRobot, make_inbox: Any) -> None:
    robot = await start(nodes=["localization", "camera", "base"])
    pose = (await (await make_inbox("pose", robot.clock)).wait_count(1))[0].value
    assert pose == {"x": 4.0, "y": 3.2, "heading_deg": 90.0, "nearest_place": "charging dock",
                    "moving": False}
    camera = (await (await make_inbox("camera", robot.clock)).wait_count(1))[0].value
    assert camera["mime_type"] == "image/jpeg"
    assert (camera["width"], camera["height"]) == (160, 120)
    jpeg = base64.b64decode(camera["data"], validate=True)
    assert jpeg[:2] == b"\xff\xd8" and jpeg[-2:] == b"\xff\xd9"
    battery = (await (await make_inbox("battery", robot.clock)).wait_count(1))[0].value
    assert isinstance(battery["percent"], float) and isinstance(battery["charging"], bool)


class _BrokenHost:
    """A node host whose `publish` fails, as a broken transport would."""

    def __init__(self, host: NodeHost) -> None:
        self._host = host

    @property
    def info(self) -> NodeInfo:
        return self._host.info

    def publish(self, topic: str, value: Any, stamp: float | None = None) -> None:
        raise RuntimeError(f"cannot publish {topic}")

    async def leave(self) -> None:
        await self._host.leave()


class _BrokenPublishing(MemoryMiddleware):
    async def host(self, info: NodeInfo, rpcs: Mapping[str, RpcHandler],
                   actions: Mapping[str, ActionHandler]) -> Any:
        return _BrokenHost(await super().host(info, rpcs, actions))


async def test_a_failing_node_loop_is_reported_not_swallowed() -> None:
    bus = _BrokenPublishing()
    robot = await start_sim_robot(bus, speed=40, nodes=["localization", "projector"])
    with pytest.raises(ExceptionGroup) as err:
        await asyncio.wait_for(robot.wait(), BOUND_S)
    assert "cannot publish pose" in str(err.value.exceptions[0])
    assert robot.failure is err.value
    # the RPCs still answer; stop still withdraws the nodes
    assert await bus.call("projector", "get_state", {}, timeout=1) == {"on": False}
    await robot.stop()
    assert bus.nodes() == {}
