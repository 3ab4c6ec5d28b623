"""Helpers for the ROS 2 tests: a ROS_DOMAIN_ID per test, foreign rclpy processes (always
reaped), and a RobotToolServer on a `ros2://` middleware with a connected MCP client."""

from __future__ import annotations

import asyncio
import itertools
import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager, suppress
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import mcp_types as types
from mcp import Client

from robovoice.mcp_server.audit import AuditLog
from robovoice.mcp_server.server import RobotToolServer
from robovoice.middleware.ros2 import Ros2Middleware
from robovoice.middleware.ros2_bridge import write_profile

from ..distributed.helpers import Child

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
MANIFESTS = HERE / "manifests"
FOREIGN = HERE / "foreign_nodes.py"
BOUND_S = 15.0
DOMAIN_FIRST, DOMAIN_LAST = 150, 230
_domains = itertools.count()


def next_domain() -> int:
    """A ROS_DOMAIN_ID of its own for each test: 150..230, spread by pytest-xdist worker."""
    worker = os.environ.get("PYTEST_XDIST_WORKER", "gw0")
    index = int(worker[2:]) if worker[2:].isdigit() else 0
    span = DOMAIN_LAST - DOMAIN_FIRST + 1
    return DOMAIN_FIRST + (index * 17 + next(_domains) + os.getpid() % 7 * 11) % span


def ros_env(domain: int, log_dir: Path) -> dict[str, str]:
    """The environment of a foreign robot process: its domain, loopback-only discovery, the
    short-lease Fast DDS profile (a kill -9 leaves the graph in ~2 s), logs out of ~/.ros."""
    return dict(os.environ, ROS_DOMAIN_ID=str(domain), ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST",
                FASTDDS_DEFAULT_PROFILES_FILE=str(write_profile(2.0)), ROS_LOG_DIR=str(log_dir),
                PYTHONUNBUFFERED="1")


class Foreign(Child):
    """A plain rclpy process (tests/ros2/foreign_nodes.py, or any argv) whose lines are collected."""

    def __init__(self, argv: list[str], env: dict[str, str]) -> None:
        super().__init__(" ".join(Path(a).name for a in argv[1:3]) or argv[0], argv, env)

    async def ready(self, needle: str = "ready", bound: float = BOUND_S) -> str:
        return await asyncio.to_thread(self.wait_for_line, needle, bound)

    def count(self, needle: str) -> int:
        return sum(needle in line for line in self.lines)

    async def counted(self, needle: str, n: int, bound: float = BOUND_S) -> int:
        """The count of lines with `needle` once it reaches `n` (lines arrive through a pipe,
        after the answer); fails after `bound` seconds."""
        deadline = time.monotonic() + bound
        while (found := self.count(needle)) < n and time.monotonic() < deadline:
            await asyncio.sleep(0.01)
        return found

    def stop(self, bound: float = 5.0) -> int:
        """SIGTERM to the whole process group (a launcher and its nodes), then SIGKILL."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGTERM)
            with suppress(subprocess.TimeoutExpired):
                self.proc.wait(bound)
        self.kill()
        return self.proc.returncode


@dataclass
class RosWorld:
    """One test's ROS 2 domain and the foreign processes started in it."""

    domain: int
    log_dir: Path
    children: list[Foreign] = field(default_factory=list)

    def start(self, *parts: str) -> Foreign:
        child = Foreign([sys.executable, str(FOREIGN), *parts], ros_env(self.domain, self.log_dir))
        self.children.append(child)
        return child

    def spawn(self, argv: list[str]) -> Foreign:
        child = Foreign(argv, ros_env(self.domain, self.log_dir))
        self.children.append(child)
        return child

    def uri(self, manifests: Path = MANIFESTS, **extra: str) -> str:
        parts = [f"domain_id={self.domain}", f"manifests={manifests}", *(f"{k}={v}" for k, v in extra.items())]
        query = "&".join(parts)
        return f"ros2://?{query}"

    def close(self) -> None:
        for child in self.children:
            child.stop()


@dataclass
class Notes:
    """A client message handler counting tools/list_changed."""

    changes: int = 0
    event: asyncio.Event = field(default_factory=asyncio.Event)

    async def __call__(self, message: Any) -> None:
        if isinstance(message, types.ToolListChangedNotification):
            self.changes += 1
            self.event.set()

    async def wait_for(self, count: int, bound: float = BOUND_S) -> None:
        async with asyncio.timeout(bound):
            while self.changes < count:
                self.event.clear()
                await self.event.wait()


@dataclass
class Served:
    middleware: Ros2Middleware
    server: RobotToolServer
    client: Client
    notes: Notes


@asynccontextmanager
async def serve(uri: str) -> AsyncIterator[Served]:
    """The ros2:// middleware, a RobotToolServer on it and an in-process MCP client."""
    middleware = Ros2Middleware.from_uri(uri)
    await middleware.start()
    try:
        server = RobotToolServer(middleware, audit=AuditLog(None))
        notes = Notes()
        async with server.running(), Client(server.server, mode="legacy", message_handler=notes) as client:
            await client.list_tools()
            yield Served(middleware, server, client, notes)
    finally:
        await middleware.close()


async def wait_tools(served: Served, names: set[str], bound: float = BOUND_S) -> None:
    """Until the client's tools/list holds exactly `names`."""
    async with asyncio.timeout(bound):
        while {t.name for t in (await served.client.list_tools()).tools} != names:
            served.notes.event.clear()
            with_timeout = asyncio.wait_for(served.notes.event.wait(), 0.5)
            with suppress(TimeoutError):
                await with_timeout


def body(result: types.CallToolResult) -> Any:
    return json.loads(next(b for b in result.content if isinstance(b, types.TextContent)).text)
