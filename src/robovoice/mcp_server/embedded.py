"""An SDK client connected in memory to a robot side running in this process.

    async with open_robot_side(SimAddress(speed=20), manifests=None, audit_log=None) as side, \
            open_embedded_client(side, message_handler=tools.handle_message) as client:
        listing = await client.list_tools()
        result = await client.call_tool("navigate_to", {"target": "kitchen"})

The client is a real `mcp.Client` connected through the SDK's in-memory transport
(``mode="legacy"``: JSON-RPC over memory streams with the ``initialize`` handshake, so it
behaves exactly as stdio/HTTP clients do: ``notifications/tools/list_changed`` reach
`message_handler`, progress reaches ``progress_callback``, cancelling the awaiting task
sends ``notifications/cancelled``). ``mode="auto"`` gives the SDK's direct in-process
2026-07-28 path instead (no JSON framing; list changes then only via ``client.listen``).
"""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from typing import Literal

import mcp_types as types
from mcp import Client
from mcp.client.session import MessageHandlerFnT

from robovoice.mcp_server._groups import unwrapped
from robovoice.mcp_server.runtime import RobotSide, wait_for_snapshots

SNAPSHOT_WARMUP_S = 2.0


@asynccontextmanager
async def open_embedded_client(
    side: RobotSide,
    *,
    message_handler: MessageHandlerFnT | None = None,
    client_name: str = "robovoice-assistant",
    mode: Literal["legacy", "auto"] = "legacy",
    snapshot_warmup_s: float = SNAPSHOT_WARMUP_S,
) -> AsyncIterator[Client]:
    """An entered `mcp.Client` of `side`'s server. It is yielded once every snapshot tool has a
    value, or after `snapshot_warmup_s` at most, and once the session is registered for list
    changes (`message_handler` receives them)."""
    async with unwrapped():
        await wait_for_snapshots(side.server, timeout=snapshot_warmup_s)
        client = Client(side.server.server, mode=mode, message_handler=message_handler, cache=None,
                        client_info=types.Implementation(name=client_name, version="embedded"))
        async with client:
            await client.list_tools()  # the session is registered for list changes once this returns
            yield client
