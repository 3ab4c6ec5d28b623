"""End to end over stdio: the SDK's real client spawns ``python -m robovoice.cli serve --robot sim``."""

from __future__ import annotations

import asyncio
import json
import sys
from pathlib import Path

import mcp_types as types
import pytest
from mcp import Client
from mcp.client.stdio import StdioServerParameters

from .mcp_testkit import BOUND_S, DRIVING, FAST, SIM_TOOLS, Progress, body


def _server(audit: Path, speed: float) -> StdioServerParameters:
    return StdioServerParameters(
        command=sys.executable,
        args=["-m", "robovoice.cli", "serve", "--robot", "sim", "--sim-speed", str(speed),
              "--audit-log", str(audit)],
    )


async def _pose(client: Client) -> dict[str, object]:
    value = body(await client.call_tool("get_robot_pose", {}))["value"]
    assert isinstance(value, dict)
    return value


async def test_stdio_tools_calls_and_audit(tmp_path: Path) -> None:
    audit = tmp_path / "audit.jsonl"
    async with Client(_server(audit, FAST), mode="legacy") as client:
        assert client.server_capabilities.tools is not None and client.server_capabilities.tools.list_changed
        assert {t.name for t in (await client.list_tools()).tools} == SIM_TOOLS
        garage = await client.call_tool("navigate_to", {"target": "garage"})
        assert garage.is_error and body(garage)["error"] == "unknown_target"
        bad = await client.call_tool("set_projector_power", {})
        assert body(bad)["error"] == "invalid_arguments"
        progress = Progress()
        kitchen = await client.call_tool("navigate_to", {"target": "kitchen"}, progress_callback=progress)
        assert not kitchen.is_error and body(kitchen)["arrived"] == "kitchen"
        assert len(progress.items) >= 2
        image = await client.call_tool("get_camera_image", {})
        assert isinstance(image.content[0], types.ImageContent)
        unsafe = await client.call_tool("set_max_speed", {"mps": 5})
        assert body(unsafe)["error"] == "unknown_tool"
    records = [json.loads(line) for line in audit.read_text().splitlines()]
    assert [r["tool"] for r in records] == ["navigate_to", "set_projector_power", "navigate_to",
                                            "get_camera_image", "set_max_speed"]
    assert records[0]["session"] is None and records[0]["client"].startswith("mcp")
    assert records[2]["outcome"] == "ok" and records[2]["result"]["arrived"] == "kitchen"


@pytest.mark.parametrize("mode", ["legacy", "auto"])
async def test_stdio_cancel_stops_the_drive(tmp_path: Path, mode: str) -> None:
    audit = tmp_path / "audit.jsonl"
    async with Client(_server(audit, DRIVING), mode=mode) as client:
        progress = Progress()
        drive = asyncio.create_task(
            client.call_tool("navigate_to", {"target": "front door"}, progress_callback=progress))
        async with asyncio.timeout(BOUND_S):
            await progress.first.wait()
            while not (await _pose(client))["moving"]:  # the pose topic lags the drive by up to a period
                pass
        drive.cancel()
        with pytest.raises(asyncio.CancelledError):
            await drive
        # the robot (in the server process) stops: poll its pose through MCP, bounded
        async with asyncio.timeout(BOUND_S):
            while (pose := await _pose(client))["moving"]:
                pass
        assert pose["nearest_place"] != "front door"
        targets = body(await client.call_tool("cancel_navigation", {}))
        assert targets["error"] == "not_driving"  # nothing left to cancel
    cancelled = [json.loads(line) for line in audit.read_text().splitlines() if '"cancelled"' in line]
    assert cancelled and cancelled[0]["tool"] == "navigate_to"
