"""Tools for people, not the model: the sim publishes its map (and call and projector state)
through MCP tools marked ``"for_model": false``; the assistant still sees exactly DESIGN.md's 12."""

from __future__ import annotations

import asyncio
import sys

import httpx

from robovoice.assistant.connect import connect_robot
from robovoice.config import RobotConfig
from robovoice.console.watch import WATCHED, RobotWatcher
from robovoice.manifest.model import FOR_MODEL_META_KEY

from .console_testkit import BOUND_S, SIM, running_console

MODEL_TOOLS = {
    "navigate_to", "get_navigation_targets", "cancel_navigation", "return_to_dock", "stop_robot",
    "set_projector_power", "start_video_call", "end_video_call", "list_contacts",
    "get_battery_state", "get_robot_pose", "get_camera_image",
}
OPERATOR_TOOLS = {"get_map", "get_call_state", "get_projector_state"}


async def test_the_assistant_sees_exactly_the_twelve_tools_and_mcp_lists_the_map_too() -> None:
    async with connect_robot(SIM) as robot:
        assert {spec.name for spec in await robot.tools.specs()} == MODEL_TOOLS
        listing = (await robot.tools.client.list_tools()).tools
        assert {t.name for t in listing} == MODEL_TOOLS | OPERATOR_TOOLS
        for tool in listing:
            assert ((tool.meta or {}).get(FOR_MODEL_META_KEY) is False) == (tool.name in OPERATOR_TOOLS)
        result = await robot.tools.client.call_tool("get_map", {})
        assert isinstance(result.structured_content, dict)
        places = {p["name"]: p for p in result.structured_content["value"]["places"]}
        assert (places["kitchen"]["x"], places["kitchen"]["y"], places["kitchen"]["reachable"]) == (2.0, 6.5, True)
        assert places["balcony"]["reachable"] is False and places["balcony"]["blocked"]


async def test_the_console_draws_from_the_robots_own_tools() -> None:
    async with running_console() as run, httpx.AsyncClient(base_url=run.base, timeout=BOUND_S) as http:
        tools = {t["name"]: t for t in (await http.get("/api/tools")).json()["tools"]}
        assert {n for n, t in tools.items() if not t["for_model"]} == OPERATOR_TOOLS
        await run.console.watcher.refresh_tools()
        for item in run.console.watcher._watched:
            await run.console.watcher.read(item)
        robot = (await http.get("/api/state")).json()["robot"]
        assert {p["name"] for p in robot["map"]["places"]} >= {"kitchen", "balcony", "charging dock"}
        assert robot["call"]["in_call"] is False and robot["projector"] == {"on": False}
        assert robot["battery"]["percent"] > 0 and robot["camera"]["mime"] == "image/jpeg"
        assert not robot["errors"]


async def test_a_robot_behind_another_processes_mcp_server_is_shown_the_same() -> None:
    """The console knows no sim: over stdio (an MCP server in a child process) the map, the pose
    and the tools come the same way."""
    robot = RobotConfig(address=f"stdio:{sys.executable} -m robovoice.cli serve --robot sim://?speed=20")
    async with running_console(robot=robot) as run, httpx.AsyncClient(base_url=run.base, timeout=BOUND_S) as http:
        await run.console.watcher.refresh_tools()
        for item in run.console.watcher._watched:
            await run.console.watcher.read(item)
        state = (await http.get("/api/state")).json()["robot"]
        assert state["pose"]["nearest_place"] == "charging dock" and len(state["map"]["places"]) == 8
        called = (await http.post("/api/call", json={"name": "navigate_to", "arguments": {"target": "hallway"}})).json()
        assert not called["is_error"] and called["structured"]["arrived"] == "hallway"


async def test_a_drive_seen_only_once_it_ended_still_leaves_its_path() -> None:
    """At speed 50 a drive can begin and end between two pose reads (CI saw an empty path):
    the path then runs from where the robot last stood to where it stands now."""
    async with connect_robot(SIM) as robot:
        watcher = RobotWatcher(robot.tools.client)
        pose = next(w for w in WATCHED if w.key == "pose")
        await watcher.read(pose)
        start = watcher.state()["pose"]
        assert watcher.state()["path"] == [] and start["moving"] is False
        done = await robot.tools.client.call_tool("navigate_to", {"target": "kitchen"})
        assert not done.is_error
        async with asyncio.timeout(BOUND_S):  # the pose snapshot lags the drive's result a little
            while True:
                await watcher.read(pose)
                now = watcher.state()["pose"]
                if now["nearest_place"] == "kitchen" and not now["moving"]:
                    break
                await asyncio.sleep(0.05)
        path = watcher.state()["path"]
        assert path[0] == [round(start["x"], 2), round(start["y"], 2)]
        assert len(path) >= 2 and path[-1] == [round(now["x"], 2), round(now["y"], 2)]
        assert abs(path[-1][0] - 2.0) < 0.1 and abs(path[-1][1] - 6.5) < 0.1  # the kitchen
        await watcher.read(pose)  # standing still afterwards adds nothing
        assert watcher.state()["path"] == path
