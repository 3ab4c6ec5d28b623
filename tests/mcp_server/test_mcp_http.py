"""End to end over streamable HTTP: the SDK's real client against a real uvicorn on loopback,
in both protocol eras (``legacy``: the 2025 ``initialize`` handshake; ``auto``: 2026-07-28)."""

from __future__ import annotations

import asyncio
import base64
import json
from pathlib import Path

import httpx2
import mcp_types as types
import pytest
from mcp import Client
from mcp.client.streamable_http import streamable_http_client

from robovoice.address import SimAddress
from robovoice.errors import ConfigError
from robovoice.manifest import ToolEntry
from robovoice.mcp_server import HttpEndpoint, RobotSide, check_bind, http_server, open_robot_side

from .mcp_testkit import (
    BOUND_S,
    DRIVING,
    SIM_PLACES,
    SIM_TOOLS,
    UNDECLARED_RPCS,
    Lamp,
    Notifications,
    Progress,
    body,
    host_lamp,
    wait_for_message,
)

MODES = ["legacy", "auto"]


@pytest.mark.parametrize("mode", MODES)
async def test_lists_exactly_the_design_tools(http: HttpEndpoint, mode: str) -> None:
    async with Client(http.url, mode=mode) as client:
        listing = await client.list_tools()
        assert client.server_capabilities.tools is not None
        assert client.server_capabilities.tools.list_changed is True
    names = [tool.name for tool in listing.tools]
    assert sorted(names) == sorted(SIM_TOOLS) and len(names) == len(SIM_TOOLS)
    navigate = next(t for t in listing.tools if t.name == "navigate_to")
    assert navigate.input_schema["required"] == ["target"]
    assert navigate.input_schema["additionalProperties"] is False
    dock = next(t for t in listing.tools if t.name == "return_to_dock")
    assert dock.input_schema["properties"] == {}  # target is fixed by the manifest, hidden from the model


async def test_every_sim_tool_works(robot: RobotSide, http: HttpEndpoint) -> None:
    sim = robot.sim
    assert sim is not None
    async with Client(http.url, mode="legacy") as client:
        async def call(name: str, **arguments: object) -> types.CallToolResult:
            return await client.call_tool(name, arguments)

        targets = await call("get_navigation_targets")
        assert not targets.is_error
        assert set(SIM_PLACES) <= {p["name"] if isinstance(p, dict) else p for p in body(targets)["places"]}

        contacts = body(await call("list_contacts"))["contacts"]
        assert {c["name"] for c in contacts} == {"Anna", "Ben", "Clara", "Dr. Weber"}

        assert not (await call("set_projector_power", on=True)).is_error
        assert sim.state.projector_on
        assert not (await call("set_projector_power", on=False)).is_error
        assert not sim.state.projector_on

        assert not (await call("start_video_call", contact="Anna")).is_error
        assert sim.state.call_contact == "Anna"
        assert not (await call("end_video_call")).is_error
        assert sim.state.call_contact is None

        arrived = await call("navigate_to", target="kitchen")
        assert not arrived.is_error, arrived
        assert body(arrived)["arrived"] == "kitchen" and sim.state.nearest_place == "kitchen"
        docked = await call("return_to_dock")
        assert not docked.is_error and body(docked)["arrived"] == "charging dock"
        assert sim.state.nearest_place == "charging dock"

        assert not (await call("stop_robot")).is_error
        not_driving = await call("cancel_navigation")
        assert not_driving.is_error and body(not_driving)["error"] == "not_driving"

        battery = await call("get_battery_state")
        assert not battery.is_error
        assert set(body(battery)) >= {"value", "stamp", "age_s", "stale"}
        assert 0 <= body(battery)["value"]["percent"] <= 100
        pose = body(await call("get_robot_pose"))
        assert pose["value"]["nearest_place"] == "charging dock" and pose["stale"] is False

        image = await call("get_camera_image")
        assert not image.is_error
        block = image.content[0]
        assert isinstance(block, types.ImageContent) and block.mime_type == "image/jpeg"
        assert base64.b64decode(block.data)[:2] == b"\xff\xd8"  # a JPEG
        about = json.loads(next(b for b in image.content if isinstance(b, types.TextContent)).text)
        assert about["stale"] is False and "data" not in about["image"]


async def test_structured_content_mirrors_the_text(http: HttpEndpoint) -> None:
    async with Client(http.url, mode="legacy") as client:
        result = await client.call_tool("list_contacts", {})
    assert result.structured_content == body(result)


@pytest.mark.parametrize("mode", MODES)
async def test_bad_arguments_never_reach_the_robot(robot: RobotSide, http: HttpEndpoint, mode: str) -> None:
    assert robot.sim is not None
    async with Client(http.url, mode=mode) as client:
        for arguments in ({}, {"target": 3}, {"target": "kitchen", "speed": 9.0}, {"target": ""}):
            result = await client.call_tool("navigate_to", arguments)
            assert result.is_error
            error = body(result)
            assert error["error"] == "invalid_arguments"
            assert error["message"] and error["hint"]
            assert error["details"]["errors"], error
            assert all(e["path"].startswith("$") and e["message"] for e in error["details"]["errors"])
            assert error["details"]["schema"]["properties"]["target"]["type"] == "string"
            assert result.structured_content == error
        fixed = body(await client.call_tool("return_to_dock", {"target": "kitchen"}))
        assert fixed["error"] == "invalid_arguments"  # a fixed default cannot be overridden
        wrong_type = body(await client.call_tool("set_projector_power", {"on": "yes"}))
        assert wrong_type["details"]["errors"][0]["path"] == "$.on"
    assert not robot.sim.state.moving and not robot.sim.state.projector_on


async def test_unknown_and_unreachable_targets(http: HttpEndpoint) -> None:
    async with Client(http.url, mode="legacy") as client:
        garage = await client.call_tool("navigate_to", {"target": "garage"})
        balcony = await client.call_tool("navigate_to", {"target": "balcony"})
        nobody = await client.call_tool("start_video_call", {"contact": "Zorro"})
    assert garage.is_error and body(garage)["error"] == "unknown_target"
    assert all(place in body(garage)["message"] for place in SIM_PLACES)
    assert body(garage)["details"]["known_places"] == SIM_PLACES
    assert body(garage)["hint"]
    assert balcony.is_error and body(balcony)["error"] == "unreachable"
    assert nobody.is_error and "Anna" in json.dumps(body(nobody))


async def test_safety_critical_rpcs_are_unreachable(robot: RobotSide, http: HttpEndpoint) -> None:
    sim = robot.sim
    assert sim is not None
    before = sim.state
    names = [*UNDECLARED_RPCS, "base.set_max_speed", "base/set_max_speed", "base:set_max_speed",
             "drive_to", "set_power", "SET_MAX_SPEED", "set_max_speed ", "stop"]
    async with Client(http.url, mode="legacy") as client:
        for name in names:
            result = await client.call_tool(name, {"mps": 3.0, "percent": 1})
            assert result.is_error and body(result)["error"] == "unknown_tool", name
            assert sorted(body(result)["details"]["available"]) == sorted(SIM_TOOLS)
        # the declared tools do not pass smuggled arguments through either
        smuggled = await client.call_tool("stop_robot", {"mps": 3.0})
        assert body(smuggled)["error"] == "invalid_arguments"
    after = sim.state
    assert after.max_speed_mps == before.max_speed_mps
    assert after.collision_avoidance is True and before.collision_avoidance is True
    # every tool served maps to an RPC its node's manifest declares, and to nothing else
    for entry in robot.server.catalog.tools():
        if isinstance(entry, ToolEntry):
            assert entry.rpc not in UNDECLARED_RPCS


@pytest.mark.parametrize("mode", MODES)
async def test_progress_notifications_during_a_drive(http: HttpEndpoint, mode: str) -> None:
    progress = Progress()
    async with Client(http.url, mode=mode) as client:
        result = await client.call_tool("navigate_to", {"target": "front door"}, progress_callback=progress)
    assert not result.is_error, result
    assert len(progress.items) >= 3
    values = [p for p, _, _ in progress.items]
    assert values == sorted(values) and values[-1] > values[0]
    totals = {t for _, t, _ in progress.items}
    assert len(totals) == 1 and next(iter(totals)) == pytest.approx(body(result)["distance_m"], abs=0.05)
    assert all(m for _, _, m in progress.items)


@pytest.mark.parametrize("mode", MODES)
async def test_cancel_during_navigate_stops_the_drive(audit_path: Path, mode: str) -> None:
    async with (open_robot_side(SimAddress(speed=DRIVING), manifests=None, audit_log=audit_path) as robot,
                http_server(robot.server) as endpoint):
        sim = robot.sim
        assert sim is not None
        async with Client(endpoint.url, mode=mode) as client:
            progress = Progress()
            drive = asyncio.create_task(
                client.call_tool("navigate_to", {"target": "front door"}, progress_callback=progress))
            async with asyncio.timeout(BOUND_S):
                await progress.first.wait()
            assert sim.state.moving and sim.state.driving_target == "front door"
            drive.cancel()
            with pytest.raises(asyncio.CancelledError):
                await drive
            stopped = await wait_for_message(robot.middleware, "pose", lambda v: v["moving"] is False)
            assert sim.state.driving_target is None and not sim.state.moving
            # the robot stays where it stopped, short of the front door
            assert stopped["nearest_place"] != "front door"
            # the server saw the cancellation: its handler was cancelled (and audited so) before the
            # node stopped the drive
            record = json.loads(audit_path.read_text().splitlines()[-1])
            assert record["tool"] == "navigate_to" and record["error"]["error"] == "cancelled"
            # and the session is still usable
            assert not (await client.call_tool("get_robot_pose", {})).is_error


async def test_list_changed_reaches_handshake_clients(robot: RobotSide, http: HttpEndpoint) -> None:
    notes = Notifications()
    lamp = Lamp()
    async with Client(http.url, mode="legacy", message_handler=notes) as client:
        assert {t.name for t in (await client.list_tools()).tools} == SIM_TOOLS
        host = await host_lamp(robot.middleware, lamp)
        await notes.wait_count(types.ToolListChangedNotification, 1)
        names = {t.name for t in (await client.list_tools()).tools}
        assert names == SIM_TOOLS | {"set_lamp", "get_lamp_level"}
        await host.leave()
        await notes.wait_count(types.ToolListChangedNotification, 2)
        assert {t.name for t in (await client.list_tools()).tools} == SIM_TOOLS


async def test_list_changed_reaches_listen_streams(robot: RobotSide, http: HttpEndpoint) -> None:
    async with Client(http.url) as client:
        assert client.protocol_version == "2026-07-28"
        async with client.listen(tools_list_changed=True) as subscription:
            host = await host_lamp(robot.middleware, Lamp())
            async with asyncio.timeout(BOUND_S):
                event = await anext(aiter(subscription))
            assert type(event).__name__ == "ToolsListChanged"
            assert "set_lamp" in {t.name for t in (await client.list_tools()).tools}
            await host.leave()
            async with asyncio.timeout(BOUND_S):
                await anext(aiter(subscription))
            assert "set_lamp" not in {t.name for t in (await client.list_tools()).tools}


async def test_audit_log_records_every_call(robot: RobotSide, http: HttpEndpoint, audit_path: Path) -> None:
    async with Client(http.url, mode="legacy") as client:
        await client.call_tool("set_projector_power", {"on": True})
        await client.call_tool("navigate_to", {"target": "garage"})
        await client.call_tool("set_max_speed", {"mps": 3})
        await client.call_tool("get_battery_state", {})
        await client.call_tool("get_camera_image", {})
    lines = [json.loads(line) for line in audit_path.read_text().splitlines()]
    assert [r["tool"] for r in lines] == ["set_projector_power", "navigate_to", "set_max_speed",
                                          "get_battery_state", "get_camera_image"]
    for record in lines:
        assert set(record) >= {"time", "session", "client", "tool", "node", "rpc", "arguments", "outcome",
                               "duration_ms"}
        assert record["session"] and record["client"].startswith("mcp")
        assert record["duration_ms"] >= 0
    power, garage, unsafe, battery, camera = lines
    assert (power["node"], power["rpc"], power["arguments"]) == ("projector", "set_power", {"on": True})
    assert power["outcome"] == "ok" and power["result"]["on"] is True
    assert garage["outcome"] == "error" and garage["error"]["error"] == "unknown_target"
    assert unsafe["node"] is None and unsafe["error"]["error"] == "unknown_tool"
    assert battery["node"] == "base" and battery["rpc"] is None and "value" in battery["result"]
    assert "data" not in json.dumps(camera["result"])  # images are not copied into the log


# --- HTTP security -------------------------------------------------------------------------

INIT = {"jsonrpc": "2.0", "id": 1, "method": "initialize",
        "params": {"protocolVersion": "2025-11-25", "capabilities": {},
                   "clientInfo": {"name": "raw", "version": "1"}}}
ACCEPT = {"Accept": "application/json, text/event-stream"}


async def _post(url: str, headers: dict[str, str]) -> httpx2.Response:
    async with httpx2.AsyncClient() as http:
        return await http.post(url, json=INIT, headers={**ACCEPT, **headers})


async def test_foreign_host_and_origin_are_rejected(http: HttpEndpoint) -> None:
    assert (await _post(http.url, {"Host": "evil.example.com"})).status_code == 421
    assert (await _post(http.url, {"Host": f"evil.example.com:{http.port}"})).status_code == 421
    assert (await _post(http.url, {"Origin": "http://evil.example.com"})).status_code == 403
    assert (await _post(http.url, {"Origin": f"http://evil.example.com:{http.port}"})).status_code == 403
    assert (await _post(http.url, {"Origin": "null"})).status_code == 403
    for good in ({}, {"Origin": f"http://localhost:{http.port}"}, {"Host": f"localhost:{http.port}"},
                 {"Origin": f"http://127.0.0.1:{http.port}"}):
        assert (await _post(http.url, good)).status_code == 200, good


async def test_token_is_required_and_checked(robot: RobotSide) -> None:
    token = "s3cret-token-of-decent-length"
    async with http_server(robot.server, token=token) as endpoint:
        missing = await _post(endpoint.url, {})
        assert missing.status_code == 401 and "Bearer" in missing.headers["www-authenticate"]
        assert (await _post(endpoint.url, {"Authorization": "Bearer wrong-token-wrong-token"})).status_code == 401
        assert (await _post(endpoint.url, {"Authorization": f"Basic {token}"})).status_code == 401
        assert (await _post(endpoint.url, {"Authorization": f"Bearer {token}x"})).status_code == 401
        assert (await _post(endpoint.url, {"Authorization": f"Bearer {token}"})).status_code == 200
        # host checks still come first with a token
        assert (await _post(endpoint.url, {"Authorization": f"Bearer {token}",
                                           "Host": "evil.example.com"})).status_code == 421
        async with httpx2.AsyncClient(headers={"Authorization": f"Bearer {token}"}) as authorised, \
                Client(streamable_http_client(endpoint.url, http_client=authorised), mode="legacy") as client:
            assert {t.name for t in (await client.list_tools()).tools} == SIM_TOOLS


def test_non_loopback_bind_needs_a_token() -> None:
    for host in ("0.0.0.0", "192.0.2.10", "::", "robot.local"):
        with pytest.raises(ConfigError, match="--token-file"):
            check_bind(host, None)
        check_bind(host, "a-token-of-some-length")
    for host in ("127.0.0.1", "localhost", "::1", "127.0.0.2"):
        check_bind(host, None)


async def test_http_server_refuses_before_binding(robot: RobotSide) -> None:
    with pytest.raises(ConfigError, match="without a bearer token"):
        async with http_server(robot.server, host="0.0.0.0", port=0):
            pytest.fail("must not start")
