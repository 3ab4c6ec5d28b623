"""The simulated robot through standard ROS 2 interfaces: a plain rclpy process (no robovoice)
drives `robovoice sim --middleware ros2://…` with nav2_msgs/NavigateToPose and switches its
projector with std_srvs/SetBool (tests/ros2/plain_nav2_client.py)."""

from __future__ import annotations

import json
import sys

import pytest

from robovoice.errors import RobotFailure
from robovoice.middleware.base import Feedback
from robovoice.middleware.ros2 import Ros2Middleware
from robovoice.middleware.ros2_standard_servers import GOAL_TOLERANCE_M, goal_place

from .ros2_testkit import HERE, RosWorld

pytestmark = pytest.mark.integration


def test_a_goal_pose_means_the_nearest_named_place() -> None:
    assert goal_place("map", 2.2, 6.3).name == "kitchen"
    assert goal_place("", 11.5, 4.0).name == "front door"
    assert goal_place("map", 9.0, 8.7).name == "balcony"  # blocked: the navigation says `unreachable`
    with pytest.raises(Exception, match=r"no named place within 1 m of \(20, 20\).*kitchen \(2, 6\.5\)") as far:
        goal_place("map", 20.0, 20.0)
    assert getattr(far.value, "code", None) == "unknown_target" and GOAL_TOLERANCE_M == 1.0
    with pytest.raises(Exception, match="goal frame 'odom' is not supported"):
        goal_place("odom", 2.0, 6.5)


async def test_a_plain_rclpy_client_drives_the_sim_with_navigate_to_pose(ros: RosWorld) -> None:
    sim = ros.spawn([sys.executable, "-m", "robovoice.cli", "sim", "--middleware", f"ros2://?domain_id={ros.domain}",
                     "--speed", "10"])
    await sim.ready("robovoice sim: ready", bound=30)
    client = ros.spawn([sys.executable, str(HERE / "plain_nav2_client.py")])
    await client.ready("done", bound=60)
    lines = client.lines

    setbool = next(line for line in lines if line.startswith("setbool "))
    assert setbool.split(" ", 2)[1] == "True" and json.loads(setbool.split(" ", 2)[2]) == {"on": True, "changed": True}

    def section(label: str) -> tuple[list[list[float]], list[str]]:
        """The feedback lines before `label`'s result line, and the result's fields."""
        end = next(i for i, line in enumerate(lines) if line.startswith(f"result {label} "))
        start = max((i for i, line in enumerate(lines[:end]) if line.startswith("result ")), default=0)
        feedback = [[float(v) for v in line.split()[1:]] for line in lines[start:end] if line.startswith("feedback ")]
        return feedback, lines[end].split(" ", 4)[2:]

    kitchen, result = section("kitchen")
    assert result[:2] == ["succeeded", "0"]
    assert len(kitchen) >= 3, kitchen
    remaining = [f[0] for f in kitchen]
    assert remaining[0] > 4.0 and remaining[-1] == 0.0 and remaining == sorted(remaining, reverse=True)
    assert kitchen[-1][1:3] == [2.0, 6.5]  # the sim's pose moved to the kitchen
    assert kitchen[-1][3] > kitchen[0][3]  # navigation_time counts up

    nowhere, result = section("nowhere")
    assert not nowhere and result[:2] == ["aborted", "9000"] and "unknown_target: no named place" in result[2]

    door, result = section("front_door")
    assert "cancel True" in lines and result[0] == "canceled" and "cancelled" in result[2]
    assert len(door) >= 3 and door[-1][0] > 1.0  # stopped well before the front door
    poses = [line for line in lines if line.startswith("pose ")]
    assert len(poses) == 2 and poses[0] == poses[1], poses  # the robot stands still after the cancel
    assert [float(v) for v in poses[0].split()[1:]] != [11.5, 4.0]


async def test_a_waypoint_manifest_drives_the_sim_through_navigate_to_pose(ros: RosWorld) -> None:
    """"Go to the kitchen" with no code: tests/ros2/sim_nav2 binds a tool to the sim's standard
    /navigate_to_pose with a table of its places, as for a Nav2 robot (docs/ros2.md, section 3)."""
    sim = ros.spawn([sys.executable, "-m", "robovoice.cli", "sim", "--middleware", f"ros2://?domain_id={ros.domain}",
                     "--speed", "10"])
    await sim.ready("robovoice sim: ready", bound=30)
    middleware = Ros2Middleware.from_uri(ros.uri(HERE / "sim_nav2"))
    await middleware.start()
    try:
        announced = middleware.nodes()["sim_nav2"].manifest
        assert announced is not None
        schema = announced["tools"][0]["parameters"]["properties"]["target"]
        assert "kitchen" in schema["enum"] and "front door" in schema["enum"]
        told: list[str] = []

        async def on_feedback(item: Feedback) -> None:
            told.append(item.message)

        result = await middleware.run_action("sim_nav2", "/navigate_to_pose", {"target": "kitchen"},
                                             on_feedback=on_feedback, timeout=30)
        assert result == {"error_code": 0, "error_msg": ""}
        assert told and told[-1] == "0.0 m to go" and float(told[0].split()[0]) > 4.0
        status = await middleware.call("navigation", "get_status", {}, timeout=5)
        assert isinstance(status, dict) and status["nearest_place"] == "kitchen" and not status["driving"]
        with pytest.raises(RobotFailure, match="garage") as bad:  # refused before anything is sent
            await middleware.run_action("sim_nav2", "/navigate_to_pose", {"target": "garage"},
                                        on_feedback=on_feedback, timeout=5)
        assert bad.value.code == "invalid_arguments"
    finally:
        await middleware.close()
