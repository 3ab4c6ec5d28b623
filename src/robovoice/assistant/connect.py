"""Connecting the assistant to a robot's MCP server: embedded, or remote over HTTP / stdio.

- embedded (`--robot sim`, or `--middleware URI [--manifests DIR]`): the robot side runs in
  this process and the SDK client talks to it in memory;
- remote (`--server http://host:port/mcp [--token-file F]`): streamable HTTP with a bearer token;
- stdio (`--server "stdio:robovoice serve --robot sim"`): the server is a child process.
"""

from __future__ import annotations

import logging
import shlex
from collections.abc import AsyncIterator
from contextlib import AsyncExitStack, asynccontextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx2
from mcp import Client
from mcp.client.stdio import StdioServerParameters
from mcp.client.streamable_http import streamable_http_client

from robovoice.assistant.robot_tools import RobotTools
from robovoice.config import read_secret_file
from robovoice.errors import ConfigError, RobotUnreachableError

log = logging.getLogger(__name__)


@dataclass(frozen=True, slots=True)
class RobotTarget:
    """Where the robot is. Exactly one of `robot`, `middleware`, `server`."""

    robot: str | None = "sim"
    middleware: str | None = None
    manifests: Path | None = None
    server: str | None = None
    token_file: Path | None = None
    sim_speed: float = 1.0

    def describe(self) -> str:
        if self.server:
            return self.server
        return f"{self.middleware} (embedded)" if self.middleware else f"{self.robot} robot (embedded)"


@dataclass
class RobotLink:
    """A connected robot: its tools for the assistant, and the sim (embedded sim only)."""

    tools: RobotTools
    sim: Any = None  # robovoice.sim.robot.SimRobot when embedded

    async def apply_setup(self, setup: str) -> None:
        if self.sim is None:
            raise ConfigError("case setups need the embedded simulated robot (--robot sim)")
        await self.sim.apply_setup(setup)


def _root_cause(exc: BaseException) -> str:
    """The innermost useful message of an exception (groups included)."""
    while isinstance(exc, BaseExceptionGroup) and exc.exceptions:
        exc = exc.exceptions[0]
    while exc.__cause__ is not None:
        exc = exc.__cause__
    return f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__


@asynccontextmanager
async def open_robot(target: RobotTarget, *, call_timeout_s: float = 330.0) -> AsyncIterator[RobotLink]:
    """Connect to the robot and yield a `RobotLink`; everything is closed on exit."""
    tools = RobotTools(call_timeout_s=call_timeout_s)
    if target.server:
        async with AsyncExitStack() as stack:
            try:
                client = await stack.enter_async_context(_remote_client(target, tools))
                tools.attach(client)
                await tools.specs()
            except ConfigError:
                raise
            except Exception as exc:  # connection refused, 401, TLS...: one clear message
                raise RobotUnreachableError(f"cannot reach the robot's MCP server at {target.server}: "
                                            f"{_root_cause(exc)}") from exc
            yield RobotLink(tools)
        return
    from robovoice.mcp_server.embedded import open_embedded_robot  # the robot side, in this process

    async with open_embedded_robot(
        robot=target.robot if not target.middleware else None,
        middleware=target.middleware,
        manifests=target.manifests,
        sim_speed=target.sim_speed,
        message_handler=tools.handle_message,
    ) as embedded:
        tools.attach(embedded.client)
        await tools.specs()
        yield RobotLink(tools, embedded.sim)


@asynccontextmanager
async def _remote_client(target: RobotTarget, tools: RobotTools) -> AsyncIterator[Client]:
    assert target.server is not None
    if target.server.startswith("stdio:"):
        argv = shlex.split(target.server[len("stdio:"):])
        if not argv:
            raise ConfigError("--server stdio: needs a command, e.g. 'stdio:robovoice serve --robot sim'")
        params = StdioServerParameters(command=argv[0], args=argv[1:])
        async with Client(params, message_handler=tools.handle_message, cache=None, mode="legacy") as client:
            yield client
        return
    if not target.server.startswith(("http://", "https://")):
        raise ConfigError(f"--server must be an http(s):// URL or 'stdio:<command>', got {target.server!r}")
    headers = {"Authorization": f"Bearer {read_secret_file(target.token_file, 'token')}"} if target.token_file else {}
    http = httpx2.AsyncClient(headers=headers, timeout=httpx2.Timeout(10.0, read=330.0))
    async with http, Client(streamable_http_client(target.server, http_client=http),
                            message_handler=tools.handle_message, cache=None, mode="legacy") as client:
        yield client
