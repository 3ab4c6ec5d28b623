"""RobotToolServer with test nodes: defaults, snapshots (fresh, stale, never received, gone),
manifest problems, presence; through the SDK client on its in-memory transport."""

from __future__ import annotations

import json
import shutil
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import mcp_types as types
import pytest
from mcp import Client

from robovoice.address import SimAddress
from robovoice.errors import ConfigError
from robovoice.mcp_server import AuditLog, RobotToolServer, open_embedded_client, open_robot_side
from robovoice.middleware.memory import MemoryMiddleware
from robovoice.snapshot import SnapshotStore

from .mcp_testkit import SIM_TOOLS, Lamp, Notifications, body, host_lamp, lamp_manifest


@dataclass
class FakeClock:
    now: float = 1000.0

    def __call__(self) -> float:
        return self.now


@dataclass
class Bench:
    middleware: MemoryMiddleware
    server: RobotToolServer
    clock: FakeClock
    client: Client
    notes: Notifications


@asynccontextmanager
async def open_bench(tmp_path: Path) -> AsyncIterator[Bench]:
    """A server on a memory bus with a fake snapshot clock, and a connected client. (Not a
    fixture: the SDK client's cancel scopes must be entered and left in the same task.)"""
    middleware = MemoryMiddleware()
    await middleware.start()
    clock = FakeClock()
    server = RobotToolServer(middleware, snapshots=SnapshotStore(clock=clock),
                             audit=AuditLog(tmp_path / "audit.jsonl"))
    notes = Notifications()
    async with server.running(), Client(server.server, mode="legacy", message_handler=notes) as client:
        await client.list_tools()  # as clients do; list changes are announced from then on
        yield Bench(middleware, server, clock, client, notes)
    await middleware.close()


async def test_fixed_defaults_are_sent_and_undeclared_rpcs_unreachable(tmp_path: Path) -> None:
    async with open_bench(tmp_path) as bench:
        lamp = Lamp()
        await host_lamp(bench.middleware, lamp)
        await bench.server.settled()
        ok = await bench.client.call_tool("set_lamp", {"on": True})
        assert not ok.is_error and body(ok) == {"on": True, "room": "hall"}
        assert lamp.calls == [("set", {"on": True, "room": "hall"})]
        override = await bench.client.call_tool("set_lamp", {"on": True, "room": "cellar"})
        assert body(override)["error"] == "invalid_arguments"
        for name in ("self_destruct", "lamp.self_destruct", "set"):
            assert body(await bench.client.call_tool(name, {}))["error"] == "unknown_tool"
        assert lamp.calls == [("set", {"on": True, "room": "hall"})]


async def test_snapshot_never_received_fresh_stale_and_gone(tmp_path: Path) -> None:
    async with open_bench(tmp_path) as bench:
        host = await host_lamp(bench.middleware, Lamp(), lamp_manifest(max_age_s=2.0))
        await bench.server.settled()

        never = await bench.client.call_tool("get_lamp_level", {})
        assert not never.is_error
        assert body(never) == {"value": None, "stamp": None, "age_s": None, "stale": True,
                               "reason": "no message received yet on 'lamp/level'"}

        host.publish("lamp/level", {"level": 0.4}, stamp=1234.5)
        fresh = body(await bench.client.call_tool("get_lamp_level", {}))
        assert fresh == {"value": {"level": 0.4}, "stamp": 1234.5, "age_s": 0.0, "stale": False}

        bench.clock.now += 1.5
        assert body(await bench.client.call_tool("get_lamp_level", {}))["stale"] is False
        bench.clock.now += 1.0  # 2.5 s old, max 2 s: stale, but still there; the call does not wait
        stale = body(await bench.client.call_tool("get_lamp_level", {}))
        assert stale == {"value": {"level": 0.4}, "stamp": 1234.5, "age_s": 2.5, "stale": True}

        await host.leave()
        await bench.notes.wait_count(types.ToolListChangedNotification, 1)
        gone = body(await bench.client.call_tool("get_lamp_level", {}))
        assert gone["error"] == "unknown_tool"

        await host_lamp(bench.middleware, Lamp(), lamp_manifest(max_age_s=2.0))
        await bench.notes.wait_count(types.ToolListChangedNotification, 2)
        back = body(await bench.client.call_tool("get_lamp_level", {}))
        assert back["value"] is None and back["stale"] is True  # the old value is not served again


async def test_snapshot_arguments_are_validated(tmp_path: Path) -> None:
    async with open_bench(tmp_path) as bench:
        await host_lamp(bench.middleware, Lamp())
        await bench.server.settled()
        result = await bench.client.call_tool("get_lamp_level", {"topic": "secret/topic"})
        assert body(result)["error"] == "invalid_arguments"


async def test_a_manifest_change_is_announced(tmp_path: Path) -> None:
    async with open_bench(tmp_path) as bench:
        await host_lamp(bench.middleware, Lamp())
        await bench.notes.wait_count(types.ToolListChangedNotification, 1)
        renamed = lamp_manifest()
        renamed["tools"][0]["name"] = "switch_lamp"
        await host_lamp(bench.middleware, Lamp(), renamed)  # the node re-announces itself
        await bench.notes.wait_count(types.ToolListChangedNotification, 2)
        names = {t.name for t in (await bench.client.list_tools()).tools}
        assert names == {"switch_lamp", "get_lamp_level"}


async def test_a_node_without_manifest_exposes_nothing_and_changes_nothing(tmp_path: Path) -> None:
    async with open_bench(tmp_path) as bench:
        from robovoice.middleware.base import NodeInfo, RpcInfo

        await bench.middleware.host(NodeInfo("silent", rpcs=(RpcInfo("reboot"),)), {}, {})
        await bench.server.settled()
        assert (await bench.client.list_tools()).tools == []
        assert bench.notes.count(types.ToolListChangedNotification) == 0


def _sim_manifests(tmp_path: Path) -> Path:
    folder = tmp_path / "manifests"
    source = resources.files("robovoice.sim").joinpath("manifests")
    shutil.copytree(str(source), folder)
    return folder


async def test_bad_manifests_leave_the_other_tools_served(tmp_path: Path) -> None:
    folder = _sim_manifests(tmp_path)
    (folder / "navigation" / "mcp.json").write_text('{"node": "navigation", "tools": [', encoding="utf-8")
    base = json.loads((folder / "base" / "mcp.json").read_text())
    base["tools"][0]["rpc"] = "set_max_speed_typo"
    (folder / "base" / "mcp.json").write_text(json.dumps(base), encoding="utf-8")
    async with (open_robot_side(SimAddress(speed=50), manifests=folder, audit_log=None) as robot,
                Client(robot.server.server, mode="legacy") as client):
        names = {t.name for t in (await client.list_tools()).tools}
        navigation = {"navigate_to", "get_navigation_targets", "cancel_navigation", "return_to_dock", "get_map"}
        assert names == SIM_TOOLS - navigation - {"stop_robot"}  # the battery snapshot of base stays
        errors = robot.server.catalog.errors()
        sources = {Path(e.source).parent.name for e in errors}
        assert sources == {"navigation", "base"}
        assert any("set_max_speed_typo" in e.message and e.path == "$.tools[0].rpc" for e in errors)
        assert body(await client.call_tool("navigate_to", {"target": "kitchen"}))["error"] == "unknown_tool"
        assert not (await client.call_tool("list_contacts", {})).is_error


async def test_a_manifest_override_cannot_reach_what_the_node_does_not_offer(tmp_path: Path) -> None:
    folder = _sim_manifests(tmp_path)
    base = json.loads((folder / "base" / "mcp.json").read_text())
    base["tools"].append({"name": "go_fast", "rpc": "set_max_speed", "description": "Faster.",
                          "parameters": {"type": "object", "properties": {"mps": {"type": "number"}}}})
    (folder / "base" / "mcp.json").write_text(json.dumps(base), encoding="utf-8")
    async with open_robot_side(SimAddress(speed=50), manifests=folder, audit_log=None) as robot:
        # declaring it is what makes an RPC reachable: the manifest folder is part of the trusted config
        assert "go_fast" in {t.name for t in robot.server.tools()}


async def test_embedded_robot_gives_a_connected_client() -> None:
    notes = Notifications()
    async with (open_robot_side(SimAddress(speed=50), manifests=None, audit_log=None) as robot,
                open_embedded_client(robot, message_handler=notes) as client):
        assert robot.sim is not None
        assert {t.name for t in (await client.list_tools()).tools} == SIM_TOOLS
        await robot.sim.apply_setup("projector_on")
        assert robot.sim.state.projector_on
        result = await client.call_tool("set_projector_power", {"on": False})
        assert not result.is_error and not robot.sim.state.projector_on
        await host_lamp(robot.middleware, Lamp())
        await notes.wait_count(types.ToolListChangedNotification, 1)


async def test_embedded_robot_lets_the_callers_errors_through() -> None:
    with pytest.raises(ConfigError, match="mine"):
        async with (open_robot_side(SimAddress(speed=50), manifests=None, audit_log=None) as robot,
                    open_embedded_client(robot)):
            raise ConfigError("mine")


async def test_unknown_robot_is_a_config_error() -> None:
    from robovoice.address import parse_robot_address

    with pytest.raises(ConfigError, match="sim://"):
        parse_robot_address("turtle://")


def test_sdk_tracing_spans_only_when_a_tracer_is_installed(monkeypatch: pytest.MonkeyPatch) -> None:
    from opentelemetry import trace

    assert RobotToolServer(MemoryMiddleware()).server.middleware == []  # no tracer: no per-call span
    monkeypatch.setattr(trace, "get_tracer_provider", lambda: trace.NoOpTracerProvider())  # one installed
    kept = RobotToolServer(MemoryMiddleware()).server.middleware
    assert [type(m).__name__ for m in kept] == ["OpenTelemetryMiddleware"]
