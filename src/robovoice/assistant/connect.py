"""The assistant's connection to a robot, whatever its address (`robovoice.address`):

- ``sim://`` or a middleware URI: the robot side runs in this process (`open_robot_side`) and
  an SDK client talks to it in memory;
- ``http(s)://host:port/mcp``: streamable HTTP, with the bearer token from `token_file`;
- ``stdio:COMMAND``: the MCP server is a child process.

    async with connect_robot(RobotConfig(address="sim://?speed=5")) as robot:
        await robot.tools.specs()
"""

from __future__ import annotations

import logging
from collections.abc import AsyncIterator, Collection
from contextlib import AsyncExitStack, asynccontextmanager
from dataclasses import dataclass
from pathlib import Path

import httpx2
from mcp import Client
from mcp.client.stdio import StdioServerParameters
from mcp.client.streamable_http import streamable_http_client

from robovoice.address import HttpAddress, MiddlewareAddress, RobotAddress, StdioAddress
from robovoice.assistant.robot_tools import RobotTools
from robovoice.config import RobotConfig, read_secret_file
from robovoice.errors import ConfigError, RobotUnreachableError
from robovoice.mcp_server._groups import unwrapped
from robovoice.mcp_server.audit import AuditLog
from robovoice.mcp_server.runtime import RobotSide, open_robot_side, wait_for_tools
from robovoice.mcp_server.tcp import nodelay_transport
from robovoice.sim import SimRobot

log = logging.getLogger(__name__)

CALL_TIMEOUT_S = 330.0  # a drive across the sim's map at speed 1 takes minutes
CONNECT_TIMEOUT_S = 10.0
# Nodes on a network middleware (ros2://, zenoh://) announce themselves one by one after a new
# participant joins: without a wait, a first turn (every case of an eval, which reconnects per
# case) was offered no tools at all.
DISCOVERY_WAIT_S = 3.0


def discovery_wait_s(target: RobotAddress) -> float:
    """How long a first turn waits for the robot's tools by default: `DISCOVERY_WAIT_S` for
    nodes on a network middleware, none for the embedded sim or an MCP server."""
    return DISCOVERY_WAIT_S if isinstance(target, MiddlewareAddress) else 0.0


@dataclass(frozen=True, slots=True)
class RobotConnection:
    """A connected robot as the assistant sees it: its `tools`, and the `side` when the robot
    runs in this process (None for an MCP server reached over HTTP or stdio)."""

    tools: RobotTools
    side: RobotSide | None = None

    @property
    def sim(self) -> SimRobot | None:
        """The embedded simulated robot, if that is the robot."""
        return self.side.sim if self.side is not None else None

    async def apply_setup(self, setup: str) -> None:
        """Establish a DESIGN.md §6 `setup` through the sim's own RPCs (not counted as MCP calls)."""
        if self.sim is None:
            raise ConfigError("case setups need the embedded simulated robot (--robot sim://)")
        await self.sim.apply_setup(setup)


def _root_cause(exc: BaseException) -> str:
    """The innermost useful message of an exception (groups included)."""
    while isinstance(exc, BaseExceptionGroup) and exc.exceptions:
        exc = exc.exceptions[0]
    while exc.__cause__ is not None:
        exc = exc.__cause__
    return f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__


@asynccontextmanager
async def connect_robot(
    config: RobotConfig,
    *,
    audit_log: Path | AuditLog | None = None,
    call_timeout_s: float = CALL_TIMEOUT_S,
    client_name: str = "robovoice-assistant",
    settle_s: float | None = None,
    tool_names: Collection[str] = (),
) -> AsyncIterator[RobotConnection]:
    """Connect to the robot `config` names and yield a `RobotConnection`; all is closed on exit.

    For a robot served here: `audit_log` (None: none) and, for nodes on a network middleware,
    `settle_s` seconds to wait for `tool_names` (or, without names, for the tool list to settle;
    default `DISCOVERY_WAIT_S` there, none for the embedded sim).
    """
    tools = RobotTools(call_timeout_s=call_timeout_s)
    target = config.target()
    if settle_s is None:
        settle_s = discovery_wait_s(target)
    if isinstance(target, HttpAddress | StdioAddress):
        async with AsyncExitStack() as stack:
            try:
                client = await stack.enter_async_context(_remote_client(target, config.token_file, tools))
                tools.attach(client)
                await tools.specs()
            except ConfigError:
                raise
            except Exception as exc:  # connection refused, 401, TLS, a child that exits...: one clear message
                raise RobotUnreachableError(f"cannot reach the robot's MCP server at {target}: "
                                            f"{_root_cause(exc)}") from exc
            yield RobotConnection(tools)
        return
    from robovoice.mcp_server.embedded import open_embedded_client

    async with (
        unwrapped(),
        open_robot_side(target, manifests=config.manifests, audit_log=audit_log) as side,
    ):
        if settle_s > 0:
            await wait_for_tools(side.server, names=tool_names, timeout=settle_s)
        async with open_embedded_client(side, message_handler=tools.handle_message,
                                        client_name=client_name) as client:
            tools.attach(client)
            await tools.specs()
            yield RobotConnection(tools, side)


@asynccontextmanager
async def _remote_client(target: HttpAddress | StdioAddress, token_file: Path | None,
                         tools: RobotTools) -> AsyncIterator[Client]:
    if isinstance(target, StdioAddress):
        params = StdioServerParameters(command=target.argv[0], args=list(target.argv[1:]))
        async with Client(params, message_handler=tools.handle_message, cache=None, mode="legacy") as client:
            yield client
        return
    headers = {"Authorization": f"Bearer {read_secret_file(token_file, 'token')}"} if token_file else {}
    http = httpx2.AsyncClient(headers=headers, timeout=httpx2.Timeout(CONNECT_TIMEOUT_S, read=CALL_TIMEOUT_S),
                              transport=nodelay_transport())  # TCP_NODELAY: no Nagle wait per call
    async with http, Client(streamable_http_client(target.url, http_client=http),
                            message_handler=tools.handle_message, cache=None, mode="legacy") as client:
        yield client
