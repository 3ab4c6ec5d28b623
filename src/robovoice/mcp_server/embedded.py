"""The embedded robot: robot, MCP server and a connected SDK client in one process.

    async with open_embedded_robot(sim_speed=20, message_handler=tools.handle_message) as robot:
        listing = await robot.client.list_tools()
        result = await robot.client.call_tool("navigate_to", {"target": "kitchen"})
        await robot.apply_setup("driving")      # the sim's own RPCs, not MCP
        robot.sim.state.moving

The client is a real `mcp.Client` connected through the SDK's in-memory transport
(``mode="legacy"``: JSON-RPC over memory streams with the ``initialize`` handshake, so it
behaves exactly as stdio/HTTP clients do: ``notifications/tools/list_changed`` reach
`message_handler`, progress reaches ``progress_callback``, cancelling the awaiting task
sends ``notifications/cancelled``). ``mode="auto"`` gives the SDK's direct in-process
2026-07-28 path instead (no JSON framing; list changes then only via ``client.listen``).
"""

from __future__ import annotations

from collections.abc import AsyncIterator, Collection
from contextlib import asynccontextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import mcp_types as types
from mcp import Client
from mcp.client.session import MessageHandlerFnT

from robovoice.errors import ConfigError
from robovoice.mcp_server._groups import unwrapped
from robovoice.mcp_server.runtime import RobotSpec, open_robot, wait_for_snapshots
from robovoice.mcp_server.server import RobotToolServer
from robovoice.middleware import Middleware
from robovoice.sim import SimRobot


@dataclass(frozen=True, slots=True)
class EmbeddedRobot:
    """A connected robot: `client` (an entered `mcp.Client`; `client.session` is its
    `ClientSession`), the `server`, the `middleware`, and the `sim` (None for a robot
    reached over a middleware URI)."""

    client: Client
    server: RobotToolServer
    middleware: Middleware
    sim: SimRobot | None

    async def apply_setup(self, setup: str) -> None:
        """Establish a DESIGN.md §6 `setup` through the sim's own RPCs (not counted as MCP calls)."""
        if self.sim is None:
            raise ConfigError("setups need the sim robot (open_embedded_robot with robot='sim')")
        await self.sim.apply_setup(setup)


@asynccontextmanager
async def open_embedded_robot(
    *,
    robot: Literal["sim"] | None = "sim",
    middleware: str | None = None,
    sim_speed: float = 1.0,
    sim_nodes: Collection[str] | None = None,
    manifests: Path | None = None,
    audit_log: Path | None = None,
    message_handler: MessageHandlerFnT | None = None,
    client_info: types.Implementation | None = None,
    mode: Literal["legacy", "auto"] = "legacy",
    snapshot_warmup_s: float = 2.0,
) -> AsyncIterator[EmbeddedRobot]:
    """Start the robot, its MCP server, and an SDK client connected to it; stop it all when
    the block ends.

    ``robot="sim"`` (the default) runs the sim robot on `middleware` (default: the in-process
    memory bus); ``robot=None`` with a `middleware` URI serves nodes that run elsewhere
    (e.g. ``zenoh://...``, with `manifests` overriding theirs). `audit_log`: a path, or None
    for no audit log. `message_handler` receives server notifications (list changes).
    It yields once every snapshot tool has a value, or after `snapshot_warmup_s` at most.
    """
    if robot not in ("sim", None):
        raise ConfigError(f"unknown robot {robot!r}: the only built-in robot is 'sim'")
    spec = RobotSpec(sim=robot == "sim", middleware_uri=middleware, manifests=manifests, sim_speed=sim_speed,
                     sim_nodes=sim_nodes, audit_log=audit_log)
    async with unwrapped(), open_robot(spec) as running:
        await wait_for_snapshots(running.server, timeout=snapshot_warmup_s)
        client = Client(
            running.server.server, mode=mode, message_handler=message_handler, cache=None,
            client_info=client_info or types.Implementation(name="robovoice-assistant", version="embedded"),
        )
        async with client:
            await client.list_tools()  # the session is registered for list changes once this returns
            yield EmbeddedRobot(client, running.server, running.middleware, running.sim)
