"""The Zenoh peer holding the rendezvous port dies (SIGKILL): the other processes, meshed
through it, keep working; its tools go and come back when it is restarted (and takes the port
again); the MCP server's audit log stays valid."""

from __future__ import annotations

import asyncio
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import mcp_types as types
import pytest
from mcp import Client

from robovoice.mcp_server.audit import read_audit
from tests.distributed.helpers import Child, free_port, sim_argv

from .test_process_faults import BOUND_S, _serve

pytestmark = pytest.mark.integration
PROJECTOR_TOOLS = {"set_projector_power", "get_projector_state"}


def body(result: types.CallToolResult) -> Any:
    return json.loads(next(b for b in result.content if isinstance(b, types.TextContent)).text)


async def _until_tools(client: Client, present: set[str], absent: set[str]) -> None:
    async with asyncio.timeout(BOUND_S):
        while True:
            names = {t.name for t in (await client.list_tools()).tools}
            if present <= names and not (absent & names):
                return
            await asyncio.sleep(0.1)


async def test_the_rendezvous_holder_dies_and_comes_back(spawn: Callable[..., Child], tmp_path: Path) -> None:
    uri = f"zenoh://127.0.0.1:{free_port()}?robot=rendezvous"
    holder = spawn("sim[projector]", sim_argv(uri, "projector"))  # first: it listens on the rendezvous port
    holder.wait_for_line("robovoice sim: ready")
    spawn("sim[rest]", sim_argv(uri, "navigation", "base", "localization", "camera", "communication",
                                speed=20)).wait_for_line("robovoice sim: ready")
    audit = tmp_path / "audit.jsonl"
    url = _serve(spawn, uri, audit)
    async with Client(url, mode="legacy") as client:
        await _until_tools(client, PROJECTOR_TOOLS | {"navigate_to"}, set())
        assert not (await client.call_tool("set_projector_power", {"on": True})).is_error

        holder.kill()  # SIGKILL the process holding the rendezvous port
        await _until_tools(client, {"navigate_to"}, PROJECTOR_TOOLS)
        drive = await client.call_tool("navigate_to", {"target": "kitchen"})  # the mesh survived
        assert not drive.is_error and body(drive)["arrived"] == "kitchen"
        gone = await client.call_tool("set_projector_power", {"on": False})
        assert gone.is_error and body(gone)["error"] in ("unknown_tool", "node_unavailable")

        spawn("sim[projector]2", sim_argv(uri, "projector")).wait_for_line("robovoice sim: ready")
        await _until_tools(client, PROJECTOR_TOOLS | {"navigate_to"}, set())
        back = await client.call_tool("get_projector_state", {})
        assert not back.is_error
        assert not (await client.call_tool("get_battery_state", {})).is_error
    reading = read_audit(audit)
    assert reading.skipped == []
    outcomes = [(r["tool"], r["outcome"]) for r in reading.records]
    assert outcomes[0] == ("set_projector_power", "ok") and ("navigate_to", "ok") in outcomes
    assert outcomes[-2:] == [("get_projector_state", "ok"), ("get_battery_state", "ok")]
