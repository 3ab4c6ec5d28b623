"""The simulated robot as real ROS 2 nodes: `robovoice sim --middleware ros2://…` in its own
process, its tools through the MCP server on `ros2://` (no manifest folder: the nodes announce
themselves), the same tools as the embedded sim, and a plain rclpy view of the graph."""

from __future__ import annotations

import asyncio
import sys
import time
from pathlib import Path

import mcp_types as types
import pytest

from robovoice.manifest import load_manifest_dir

from .ros2_testkit import BOUND_S, RosWorld, body, serve, wait_tools

pytestmark = pytest.mark.integration

SIM_MANIFESTS = Path(__file__).resolve().parents[2] / "src" / "robovoice" / "sim" / "manifests"


def sim_tools() -> set[str]:
    loaded = load_manifest_dir(SIM_MANIFESTS)
    names = {t.name for m in loaded.manifests.values() for t in m.manifest.tools}
    return names | {s.name for m in loaded.manifests.values() for s in m.manifest.snapshots}


async def test_the_sim_robot_on_ros2_serves_the_same_tools(ros: RosWorld) -> None:
    sim = ros.spawn([sys.executable, "-m", "robovoice.cli", "sim", "--middleware", f"ros2://?domain_id={ros.domain}",
                     "--speed", "10"])
    await sim.ready("robovoice sim: ready", bound=30)
    expected = sim_tools()
    assert {"navigate_to", "get_battery_state", "start_video_call", "get_camera_image"} <= expected
    async with serve(f"ros2://?domain_id={ros.domain}") as served:
        await wait_tools(served, expected)
        told: list[str | None] = []

        async def on_progress(progress: float, total: float | None, message: str | None) -> None:
            told.append(message)

        drive = await served.client.call_tool("navigate_to", {"target": "kitchen"}, progress_callback=on_progress)
        assert not drive.is_error and body(drive)["arrived"] == "kitchen"
        assert told and told[-1] == "arrived at the kitchen"
        balcony = await served.client.call_tool("navigate_to", {"target": "balcony"})
        assert balcony.is_error and body(balcony)["error"] == "unreachable"
        call = await served.client.call_tool("start_video_call", {"contact": "Anna"})
        assert not call.is_error and body(call)["contact"] == "Anna"

        async with asyncio.timeout(BOUND_S):
            while body(pose := await served.client.call_tool("get_robot_pose", {})).get("value") is None:
                await asyncio.sleep(0.05)
        assert body(pose)["value"]["nearest_place"] == "kitchen"
        async with asyncio.timeout(BOUND_S):
            while not any(isinstance(b, types.ImageContent)
                          for b in (await served.client.call_tool("get_camera_image", {})).content):
                await asyncio.sleep(0.05)

        started = asyncio.Event()

        async def first(progress: float, total: float | None, message: str | None) -> None:
            started.set()

        long = asyncio.create_task(served.client.call_tool("navigate_to", {"target": "front door"},
                                                           progress_callback=first))
        await asyncio.wait_for(started.wait(), BOUND_S)
        long.cancel()  # cancels the goal on the sim's ROS 2 action server, which stops the drive
        with pytest.raises(asyncio.CancelledError):
            await long
        async with asyncio.timeout(BOUND_S):
            while body(await served.client.call_tool("get_robot_pose", {}))["value"]["moving"]:
                await asyncio.sleep(0.1)

        # a plain rclpy view: the navigation is an action server, the battery a topic
        actions = dict(served.middleware.graph_actions())
        assert "robovoice_msgs/action/Run" in actions["/robovoice/navigation/drive_to"]
        assert "nav2_msgs/action/NavigateToPose" in actions["/navigate_to_pose"]  # test_ros2_sim_standard drives it

        # and a plain rclpy process sees the battery as sensor_msgs/BatteryState (a standard mirror)
        plain = ros.spawn([sys.executable, "-c", _PLAIN_BATTERY])
        line = await plain.ready("battery", bound=BOUND_S)
        assert 0.0 < float(line.split()[1]) <= 1.0

        changes = served.notes.changes
        sim.kill()
        killed = time.monotonic()
        await served.notes.wait_for(changes + 1)
        await wait_tools(served, set())
        assert time.monotonic() - killed < 6.0


async def test_eval_against_the_sim_on_ros2_scores_as_in_process(ros: RosWorld) -> None:
    """`robovoice eval … --robot ros2://…` with the sim's nodes in another process (a scripted
    model: the scoring and the robot are what is tested, not the model)."""
    import json
    import subprocess

    from robovoice.llm.fake_server import (
        CallbackReply,
        FakeOpenAIServer,
        RecordedRequest,
        ScriptedCall,
        TextReply,
        ToolCallReply,
    )

    from .ros2_testkit import ROOT, ros_env

    sim = ros.spawn([sys.executable, "-m", "robovoice.cli", "sim", "--middleware", f"ros2://?domain_id={ros.domain}",
                     "--speed", "50"])
    await sim.ready("robovoice sim: ready", bound=30)

    def reply(request: RecordedRequest) -> ToolCallReply | TextReply:
        if request.messages[-1]["role"] == "tool":
            return TextReply("Done.")
        # a call only when the tool is offered: each case reconnects, and a case run before the
        # sim's nodes were discovered was offered no tools at all (now connect_robot waits)
        if "kitchen" in request.last_user_text.lower() and "navigate_to" in request.tool_names:
            return ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),))
        return TextReply("Hello!")

    async with FakeOpenAIServer([], default=CallbackReply(reply)) as llm:
        run = await asyncio.to_thread(
            subprocess.run, [sys.executable, "-m", "robovoice.cli", "eval", str(ROOT / "tests/data/eval/text.jsonl"),
                             "--robot", f"ros2://?domain_id={ros.domain}", "--only", "nav-kitchen-1",
                             "--only", "chat-1", "--only", "proj-on-1", "--llm", llm.base_url, "--model", llm.model,
                             "--json"],
            cwd=ROOT, capture_output=True, text=True, env=ros_env(ros.domain, ros.log_dir), timeout=240, check=False)
    assert run.returncode == 0, run.stderr
    summary = json.loads(run.stdout)
    assert summary["cases"] == 3 and summary["passed"] == 2  # as tests/test_cli_assistant.py in-process


_PLAIN_BATTERY = """
import rclpy
from sensor_msgs.msg import BatteryState
rclpy.init()
node = rclpy.create_node("plain_listener")
def got(msg):
    print("battery", msg.percentage, flush=True)
node.create_subscription(BatteryState, "/battery_state", got, 10)
rclpy.spin(node)
"""
