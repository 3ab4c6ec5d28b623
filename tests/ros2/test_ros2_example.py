"""examples/ros2_robot end to end, all real processes: the plain rclpy robot, `robovoice
tools`/`call` on its manifests, and `robovoice serve --transport http` with the MCP client."""

from __future__ import annotations

import asyncio
import json
import re
import subprocess
import sys
import time

import pytest
from mcp import Client

from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedCall, ScriptedReply, TextReply, ToolCallReply

from .ros2_testkit import BOUND_S, ROOT, Notes, RosWorld, body, ros_env

pytestmark = pytest.mark.integration

EXAMPLE = ROOT / "examples" / "ros2_robot"
TOOLS = {"navigate_to", "return_to_dock", "stop_robot", "set_projector_power", "get_battery_state",
         "get_camera_image"}


def robovoice(ros: RosWorld, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "robovoice.cli", *args], cwd=ROOT, capture_output=True, text=True,
                          env=ros_env(ros.domain, ros.log_dir), timeout=60, check=False)


async def test_the_example_robot_through_robovoice_call(ros: RosWorld) -> None:
    robot = ros.spawn([sys.executable, str(EXAMPLE / "robot.py"), "--speed", "20"])
    await robot.ready("robot ready")
    uri = ros.uri(EXAMPLE / "manifests")
    listed = await asyncio.to_thread(robovoice, ros, "tools", "--middleware", uri, "--json")
    assert listed.returncode == 0, listed.stderr
    assert {t["name"] for t in json.loads(listed.stdout)} == TOOLS

    drive = await asyncio.to_thread(robovoice, ros, "call", "--middleware", uri, "navigate_to", "target=kitchen")
    assert drive.returncode == 0, drive.stderr + drive.stdout
    assert json.loads(drive.stdout.strip().splitlines()[-1]) == {"error_code": 0, "error_msg": ""}
    assert "m to go" in drive.stdout + drive.stderr  # feedback became progress

    garage = await asyncio.to_thread(robovoice, ros, "call", "--middleware", uri, "navigate_to", "target=garage")
    assert garage.returncode == 1 and "invalid_arguments" in garage.stdout + garage.stderr
    battery = await asyncio.to_thread(robovoice, ros, "call", "--middleware", uri, "get_battery_state")
    assert battery.returncode == 0 and json.loads(battery.stdout)["value"]["voltage"] == 25.2


async def test_the_example_robot_through_robovoice_serve(ros: RosWorld) -> None:
    robot = ros.spawn([sys.executable, str(EXAMPLE / "robot.py"), "--speed", "5"])
    await robot.ready("robot ready")
    server = ros.spawn([sys.executable, "-m", "robovoice.cli", "serve", "--middleware", ros.uri(EXAMPLE / "manifests"),
                        "--transport", "http", "--port", "0", "--no-audit-log"])
    match = re.search(r"ready: (\S+)", await server.ready("robovoice serve: ready", bound=30))
    assert match is not None
    notes = Notes()
    async with Client(match.group(1), mode="legacy", message_handler=notes) as client:
        async with asyncio.timeout(BOUND_S):
            while {t.name for t in (await client.list_tools()).tools} != TOOLS:
                await asyncio.sleep(0.1)
        told: list[str | None] = []

        async def on_progress(progress: float, total: float | None, message: str | None) -> None:
            told.append(message)

        result = await client.call_tool("navigate_to", {"target": "hallway"}, progress_callback=on_progress)
        assert not result.is_error, body(result)
        assert told and all(m is not None and m.endswith("m to go") for m in told)

        changes = notes.changes
        robot.kill()
        killed = time.monotonic()
        await notes.wait_for(changes + 1)
        assert time.monotonic() - killed < 4.0
        assert {t.name for t in (await client.list_tools()).tools} == set()


async def test_the_example_robot_talks_through_robovoice_chat(ros: RosWorld) -> None:
    """`robovoice chat --robot ros2://…` with a scripted model (the embedded one works too, only slower)."""
    robot = ros.spawn([sys.executable, str(EXAMPLE / "robot.py"), "--speed", "20"])
    await robot.ready("robot ready")
    script: list[ScriptedReply] = [ToolCallReply((ScriptedCall("navigate_to", {"target": "bedroom"}),)),
                                   TextReply("I'm in the bedroom now.")]
    async with FakeOpenAIServer(script) as llm:
        chat = await asyncio.to_thread(
            subprocess.run, [sys.executable, "-m", "robovoice.cli", "chat", "--robot", ros.uri(EXAMPLE / "manifests"),
                             "--llm", llm.base_url, "--model", llm.model],
            cwd=ROOT, input="please drive to the bedroom\n", capture_output=True, text=True,
            env=ros_env(ros.domain, ros.log_dir), timeout=120, check=False)
    assert chat.returncode == 0, chat.stderr
    assert "→ navigate_to(target='bedroom')" in chat.stdout
    assert '← navigate_to ok' in chat.stdout and "m to go" in chat.stdout
    assert "robot> I'm in the bedroom now." in chat.stdout
