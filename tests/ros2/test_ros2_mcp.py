"""Real ROS 2 end to end: plain rclpy processes that know nothing of robovoice (a service, an
action with feedback and cancel, a 10 Hz topic, images) reached through the MCP server on a
`ros2://` middleware, with the real MCP client. Crashes are real (SIGKILL)."""

from __future__ import annotations

import asyncio
import base64
import signal
import sys
import time

import mcp_types as types
import pytest
from mcp import Client

from .ros2_testkit import BOUND_S, RosWorld, body, serve, wait_tools

pytestmark = pytest.mark.integration

ALL = {"set_projector_power", "count_fibonacci", "count_named", "count_briefly", "get_battery_state",
       "get_camera_image", "get_compressed_image", "echo_basic"}


async def test_service_action_and_snapshots_through_mcp(ros: RosWorld) -> None:
    robot = ros.start("projector", "fibonacci", "battery", "camera", "basic")
    await robot.ready()
    async with serve(ros.uri()) as served:
        await wait_tools(served, ALL)
        tools = {t.name: t for t in (await served.client.list_tools()).tools}
        assert tools["set_projector_power"].input_schema["properties"]["on"]["type"] == "boolean"
        assert tools["set_projector_power"].input_schema["required"] == ["on"]
        order = tools["count_fibonacci"].input_schema["properties"]["order"]
        assert order["minimum"] == -(2**31) and order["description"] == "how many numbers"

        on = await served.client.call_tool("set_projector_power", {"on": True})
        assert not on.is_error and body(on) == {"success": True, "message": "projector on"}
        assert await robot.counted("request /projector/set_power data=True", 1) == 1

        seen: list[tuple[float, str | None]] = []

        async def on_progress(progress: float, total: float | None, message: str | None) -> None:
            seen.append((progress, message))

        result = await served.client.call_tool("count_fibonacci", {"order": 6}, progress_callback=on_progress)
        assert not result.is_error and body(result) == {"sequence": [0, 1, 1, 2, 3, 5, 8]}
        assert [p for p, _ in seen] == [1.0, 2.0, 3.0, 4.0, 5.0]
        assert seen[-1][1] == "[0, 1, 1, 2, 3, 5, 8] so far"

        async with asyncio.timeout(BOUND_S):  # the 10 Hz topic reaches the snapshot buffer
            while body(battery := await served.client.call_tool("get_battery_state", {})).get("value") is None:
                await asyncio.sleep(0.05)
        snap = body(battery)
        assert snap["stale"] is False and snap["value"]["voltage"] == 24.1
        assert set(snap["value"]) == {"percentage", "voltage", "power_supply_status"}

        image = await _image(served.client, "get_camera_image")
        assert image.mime_type == "image/png" and base64.b64decode(image.data).startswith(b"\x89PNG")
        jpeg = await _image(served.client, "get_compressed_image")
        assert jpeg.mime_type == "image/jpeg" and base64.b64decode(jpeg.data).startswith(b"\xff\xd8")


async def _image(client: Client, tool: str) -> types.ImageContent:
    """The image block of the snapshot tool, once a frame has arrived."""
    async with asyncio.timeout(BOUND_S):
        while True:
            result = await client.call_tool(tool, {})
            for block in result.content:
                if isinstance(block, types.ImageContent):
                    return block
            await asyncio.sleep(0.05)


async def test_named_choices_fixed_fields_and_refusals_before_sending(ros: RosWorld) -> None:
    robot = ros.start("fibonacci", "basic")
    await robot.ready()
    async with serve(ros.uri()) as served:
        await wait_tools(served, {"count_fibonacci", "count_named", "count_briefly", "echo_basic"})
        named = await served.client.call_tool("count_named", {"length": "short"})
        assert not named.is_error and body(named)["sequence"] == [0, 1, 1, 2]
        assert await robot.counted("goal /fibonacci order=3", 1) == 1
        unknown = await served.client.call_tool("count_named", {"length": "medium"})
        assert unknown.is_error and body(unknown)["error"] == "invalid_arguments"

        echo = await served.client.call_tool("echo_basic", {"int8_value": -5, "float32_value": 1.5})
        assert not echo.is_error
        assert body(echo)["int8_value"] == -5 and body(echo)["string_value"] == "fixed"
        sent = await robot.counted("request /basic/echo", 1)
        for bad in ({"int8_value": 300}, {"uint8_value": -1}, {"float32_value": "abc"},
                    {"int16_value": 1.5}, {"bool_value": 1}, {"string_value": "x"}, {"float32_value": 1e39}):
            refused = await served.client.call_tool("echo_basic", bad)
            assert refused.is_error, bad
            assert body(refused)["error"] == "invalid_arguments", (bad, body(refused))
        # an integral float in a float field is converted, not zeroed (rclpy would send 0.0)
        converted = await served.client.call_tool("echo_basic", {"float64_value": 7})
        assert body(converted)["float64_value"] == 7.0
        assert await robot.counted("request /basic/echo", sent + 1) == sent + 1  # none of the bad ones was sent


async def test_rejected_aborted_and_cancelled_goals(ros: RosWorld) -> None:
    robot = ros.start("fibonacci")
    await robot.ready()
    async with serve(ros.uri()) as served:
        await wait_tools(served, {"count_fibonacci", "count_named", "count_briefly"})
        rejected = await served.client.call_tool("count_fibonacci", {"order": 41})
        assert rejected.is_error and body(rejected)["error"] == "goal_rejected"
        aborted = await served.client.call_tool("count_named", {"length": "unlucky"})
        assert aborted.is_error and body(aborted)["error"] == "aborted"
        assert len(body(aborted)["details"]["result"]["sequence"]) == 14

        started = asyncio.Event()

        async def on_progress(progress: float, total: float | None, message: str | None) -> None:
            started.set()

        long = asyncio.create_task(served.client.call_tool("count_named", {"length": "long"},
                                                           progress_callback=on_progress))
        await asyncio.wait_for(started.wait(), BOUND_S)
        long.cancel()
        with pytest.raises(asyncio.CancelledError):
            await long
        await robot.ready("canceled /fibonacci")  # the goal on the robot was cancelled
        again = await served.client.call_tool("count_named", {"length": "short"})
        assert not again.is_error

        cancels = robot.count("canceled /fibonacci")
        brief = await served.client.call_tool("count_briefly", {})  # times out after 0.5 s
        assert brief.is_error and body(brief)["error"] == "timeout"
        assert await robot.counted("canceled /fibonacci", cancels + 1) == cancels + 1  # and was cancelled


async def test_fifty_concurrent_calls_are_all_answered(ros: RosWorld) -> None:
    robot = ros.start("projector")
    await robot.ready()
    async with serve(ros.uri()) as served:
        await wait_tools(served, {"set_projector_power"})
        results = await asyncio.gather(*(served.client.call_tool("set_projector_power", {"on": i % 2 == 0})
                                         for i in range(50)))
        assert [r.is_error for r in results] == [False] * 50
        assert await robot.counted("request /projector/set_power", 50) == 50


async def test_kill_9_removes_the_tools_and_a_restart_brings_them_back(ros: RosWorld) -> None:
    robot = ros.start("projector", "battery")
    await robot.ready()
    async with serve(ros.uri()) as served:
        await wait_tools(served, {"set_projector_power", "get_battery_state"})
        changes = served.notes.changes
        robot.kill()
        killed = time.monotonic()
        await served.notes.wait_for(changes + 1)
        noticed = time.monotonic() - killed
        await wait_tools(served, set())
        assert noticed < 4.0, f"the dead node was noticed after {noticed:.2f} s"
        gone = await served.client.call_tool("set_projector_power", {"on": True})
        assert gone.is_error

        again = ros.start("projector", "battery")
        await again.ready()
        await wait_tools(served, {"set_projector_power", "get_battery_state"})
        assert not (await served.client.call_tool("set_projector_power", {"on": False})).is_error


async def test_action_server_killed_mid_goal_is_a_bounded_node_unavailable(ros: RosWorld) -> None:
    robot = ros.start("fibonacci")
    await robot.ready()
    async with serve(ros.uri()) as served:
        await wait_tools(served, {"count_fibonacci", "count_named", "count_briefly"})
        started = asyncio.Event()

        async def on_progress(progress: float, total: float | None, message: str | None) -> None:
            started.set()

        goal = asyncio.create_task(served.client.call_tool("count_named", {"length": "long"},
                                                           progress_callback=on_progress))
        await asyncio.wait_for(started.wait(), BOUND_S)
        robot.kill()
        killed = time.monotonic()
        result = await asyncio.wait_for(goal, BOUND_S)
        assert result.is_error and body(result)["error"] == "node_unavailable", body(result)
        assert time.monotonic() - killed < 5.0


async def test_stale_and_never_received_snapshots(ros: RosWorld) -> None:
    robot = ros.start("battery")
    await robot.ready()
    async with serve(ros.uri()) as served:
        await wait_tools(served, {"get_battery_state"})
        async with asyncio.timeout(BOUND_S):
            while body(await served.client.call_tool("get_battery_state", {})).get("value") is None:
                await asyncio.sleep(0.05)
        robot.proc.send_signal(signal.SIGSTOP)  # frozen: still in the graph, silent
        try:
            async with asyncio.timeout(BOUND_S):  # max_age_s is 1 s
                while not body(snap := await served.client.call_tool("get_battery_state", {}))["stale"]:
                    await asyncio.sleep(0.1)
            assert body(snap)["value"] is not None and body(snap)["age_s"] > 1.0
        finally:
            robot.kill()


async def test_a_topic_with_a_silent_publisher_is_never_received(ros: RosWorld) -> None:
    # a publisher on /battery_state that never publishes: the tool is there, the value is not
    silent = ros.spawn([sys.executable, "-c", _SILENT])
    await silent.ready()
    async with serve(ros.uri()) as served:
        await wait_tools(served, {"get_battery_state"})
        snap = body(await served.client.call_tool("get_battery_state", {}))
        assert snap["value"] is None and snap["stale"] is True and "no message" in snap["reason"]


_SILENT = """
import rclpy, threading
from sensor_msgs.msg import BatteryState
rclpy.init()
node = rclpy.create_node("silent_battery")
node.create_publisher(BatteryState, "/battery_state", 10)
print("ready", flush=True)
rclpy.spin(node)
"""
