"""End to end across processes: sim nodes (`robovoice sim`), the MCP server (`robovoice serve
--transport http`) and an MCP client (the `mcp` SDK, in the test), all joined by Zenoh on
loopback. Crashes are real: SIGKILL and SIGSTOP of node processes."""

from __future__ import annotations

import asyncio
import json
import re
import signal
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import mcp_types as types
import pytest
from mcp import Client

from .helpers import ROOT, Child, free_port, robovoice, sim_argv

pytestmark = pytest.mark.integration

BOUND_S = 10.0
SIM_TOOLS = frozenset({
    "navigate_to", "get_navigation_targets", "cancel_navigation", "return_to_dock", "stop_robot",
    "set_projector_power", "start_video_call", "end_video_call", "list_contacts",
    "get_battery_state", "get_robot_pose", "get_camera_image",
}) | {"get_map", "get_call_state", "get_projector_state"}  # + tools for people (the console), not the model
NAVIGATION_TOOLS = {"navigate_to", "get_navigation_targets", "cancel_navigation", "return_to_dock", "get_map"}


@dataclass
class Notifications:
    """A client `message_handler` counting tools/list_changed notifications."""

    changes: int = 0
    _event: asyncio.Event = field(default_factory=asyncio.Event)

    async def __call__(self, message: Any) -> None:
        if isinstance(message, types.ToolListChangedNotification):
            self.changes += 1
            self._event.set()

    async def wait_for(self, count: int, bound: float = BOUND_S) -> None:
        async with asyncio.timeout(bound):
            while self.changes < count:
                self._event.clear()
                await self._event.wait()


def body(result: types.CallToolResult) -> Any:
    return json.loads(next(b for b in result.content if isinstance(b, types.TextContent)).text)


async def tool_names(client: Client) -> set[str]:
    return {tool.name for tool in (await client.list_tools()).tools}


class Robot:
    """Sim node processes and one MCP server process on a fresh Zenoh rendezvous port."""

    def __init__(self, spawn: Callable[..., Child]) -> None:
        self.spawn = spawn
        self.uri = f"zenoh://127.0.0.1:{free_port()}?robot=e2e"

    def sim(self, *nodes: str, speed: float = 1.0) -> Child:
        child = self.spawn(f"sim[{','.join(nodes)}]", sim_argv(self.uri, *nodes, speed=speed))
        child.wait_for_line("robovoice sim: ready")
        return child

    def serve(self) -> str:
        server = self.spawn("serve", robovoice("serve", "--middleware", self.uri, "--transport", "http",
                                               "--port", str(free_port()), "--no-audit-log"))
        match = re.search(r"ready: (\S+)", server.wait_for_line("robovoice serve: ready", bound=20))
        assert match is not None
        return match.group(1)


async def test_navigation_crash_mid_drive_and_restart(spawn: Callable[..., Child]) -> None:
    robot = Robot(spawn)
    robot.sim("base", "localization", "camera", "projector", "communication", speed=5)
    navigation = robot.sim("navigation")
    url = robot.serve()
    notes = Notifications()
    async with Client(url, mode="legacy", message_handler=notes) as client:
        assert await tool_names(client) == SIM_TOOLS
        targets = await client.call_tool("get_navigation_targets", {})
        assert not targets.is_error and "kitchen" in body(targets)["places"]

        started = asyncio.Event()

        async def on_progress(progress: float, total: float | None, message: str | None) -> None:
            started.set()

        drive = asyncio.create_task(client.call_tool("navigate_to", {"target": "front door"},
                                                     progress_callback=on_progress))
        await asyncio.wait_for(started.wait(), BOUND_S)
        navigation.kill()
        killed = asyncio.get_running_loop().time()
        result = await asyncio.wait_for(drive, BOUND_S)
        assert result.is_error and body(result)["error"] in ("node_unavailable", "timeout")
        assert asyncio.get_running_loop().time() - killed < 5.0
        await notes.wait_for(1)
        assert await tool_names(client) == SIM_TOOLS - NAVIGATION_TOOLS

        robot.sim("navigation")
        await notes.wait_for(2)
        assert await tool_names(client) == SIM_TOOLS
        targets = await client.call_tool("get_navigation_targets", {})
        assert not targets.is_error, targets


async def test_snapshot_of_a_frozen_then_dead_publisher(spawn: Callable[..., Child]) -> None:
    robot = Robot(spawn)
    localization = robot.sim("localization")
    url = robot.serve()
    notes = Notifications()
    async with Client(url, mode="legacy", message_handler=notes) as client:
        assert await tool_names(client) == {"get_robot_pose"}
        async with asyncio.timeout(BOUND_S):  # the first pose message reaches the server's buffer
            while (pose := await client.call_tool("get_robot_pose", {})).is_error or body(pose).get("reason"):
                await asyncio.sleep(0.05)
        assert body(pose)["stale"] is False and "x" in body(pose)["value"]

        localization.proc.send_signal(signal.SIGSTOP)  # frozen: its link stays up, messages stop
        try:
            async with asyncio.timeout(BOUND_S):  # max_age_s is 1 s
                while not body(pose := await client.call_tool("get_robot_pose", {}))["stale"]:
                    await asyncio.sleep(0.1)
            assert body(pose)["value"] is not None and body(pose)["age_s"] > 1
        finally:
            localization.kill()  # SIGKILL works on a stopped process
        await notes.wait_for(1)
        assert await tool_names(client) == set()
        gone = await client.call_tool("get_robot_pose", {})
        assert gone.is_error


async def test_external_zenoh_node_becomes_tools(spawn: Callable[..., Child]) -> None:
    robot = Robot(spawn)
    url = robot.serve()
    port = robot.uri.split(":")[2].split("?")[0]
    notes = Notifications()
    async with Client(url, mode="legacy", message_handler=notes) as client:
        assert await tool_names(client) == set()
        lights = spawn("lights", [sys.executable, str(ROOT / "examples" / "zenoh_external_node.py"),
                                  "--connect", f"tcp/127.0.0.1:{port}", "--robot", "e2e", "--period", "0.2"])
        lights.wait_for_line("lights: ready")
        await notes.wait_for(1)
        assert await tool_names(client) == {"set_light", "list_lights", "get_indoor_temperature"}
        switched = await client.call_tool("set_light", {"room": "kitchen", "on": True})
        assert not switched.is_error and body(switched) == {"room": "kitchen", "on": True}
        refused = await client.call_tool("set_light", {"room": "garage", "on": True})
        assert refused.is_error and body(refused)["error"] == "unknown_room"
        async with asyncio.timeout(BOUND_S):
            while body(temperature := await client.call_tool("get_indoor_temperature", {})).get("reason"):
                await asyncio.sleep(0.05)
        assert 20 < body(temperature)["value"]["celsius"] < 23


async def test_serve_with_an_unreachable_middleware_fails_clearly(spawn: Callable[..., Child]) -> None:
    port = free_port()
    server = spawn("serve-unreachable", robovoice(
        "serve", "--middleware", f"zenoh://127.0.0.1:{port}?mode=client&timeout=0.5",
        "--transport", "http", "--port", str(free_port()), "--no-audit-log"))
    code = await asyncio.to_thread(server.proc.wait, 15)
    server.stop()
    assert code == 1, server.output()
    assert f"tcp/127.0.0.1:{port}" in server.output()
