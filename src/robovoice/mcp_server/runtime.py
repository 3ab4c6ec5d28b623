"""The robot side: the middleware, the sim robot (or the nodes behind a middleware URI), the
manifests, the audit log and the `RobotToolServer`, started and stopped as one.

    async with open_robot_side(SimAddress(speed=20), manifests=None, audit_log=None) as side:
        side.server   # RobotToolServer, already following presence
        side.sim      # SimRobot, or None when the nodes are on the far side of a middleware URI
"""

from __future__ import annotations

import asyncio
import logging
import math
from collections.abc import AsyncIterator, Collection
from contextlib import AsyncExitStack, asynccontextmanager
from dataclasses import dataclass
from pathlib import Path

from robovoice.address import LocalAddress, MiddlewareAddress, SimAddress
from robovoice.errors import ConfigError
from robovoice.manifest import ManifestSet, SnapshotEntry, format_error, load_manifest_dir
from robovoice.mcp_server.audit import AuditLog
from robovoice.mcp_server.server import RobotToolServer
from robovoice.middleware import Middleware, open_middleware
from robovoice.middleware.base import Message
from robovoice.sim import SimRobot, start_sim_robot
from robovoice.snapshot import SnapshotStore, UntrackedTopicError

log = logging.getLogger(__name__)

SIM_MIDDLEWARE = "memory://"
DEFAULT_SIM_SPEED = 1.0  # simulated seconds per real second where neither address nor command says


@dataclass(frozen=True, slots=True)
class RobotSide:
    """A robot served from this process: its `middleware`, the MCP `server` built from the
    manifests of the nodes present, and the `sim` (None for nodes behind a middleware URI)."""

    middleware: Middleware
    server: RobotToolServer
    sim: SimRobot | None


def load_override(folder: Path | None) -> ManifestSet | None:
    """Load a manifest folder; its bad files are reported (their nodes then expose nothing)."""
    if folder is None:
        return None
    loaded = load_manifest_dir(folder)
    if not loaded.manifests and loaded.errors and not loaded.failed:
        raise ConfigError("; ".join(format_error(e) for e in loaded.errors))
    for error in loaded.errors:
        log.warning("manifest not used: %s", format_error(error))
    return loaded


@asynccontextmanager
async def open_robot_side(address: LocalAddress, *, manifests: Path | None,
                          audit_log: Path | AuditLog | None) -> AsyncIterator[RobotSide]:
    """Start the robot side `address` names (`manifests`: a folder replacing the nodes' own;
    `audit_log`: a path, an `AuditLog` (its rotation settings), or None for none); stop it all
    (sim, server, middleware, audit log) on the way out."""
    override = load_override(manifests)
    match address:
        case SimAddress():
            middleware = open_middleware(SIM_MIDDLEWARE)
        case MiddlewareAddress(uri=uri):
            middleware = open_middleware(uri)
    async with AsyncExitStack() as stack:
        await middleware.start()
        stack.push_async_callback(middleware.close)
        sim: SimRobot | None = None
        if isinstance(address, SimAddress):
            speed = DEFAULT_SIM_SPEED if address.speed is None else address.speed
            sim = await start_sim_robot(middleware, speed=speed, nodes=address.nodes)
            stack.push_async_callback(sim.stop)
        audit = audit_log if isinstance(audit_log, AuditLog) else AuditLog(audit_log)
        stack.callback(audit.close)
        server = RobotToolServer(middleware, manifests=override, audit=audit)
        await stack.enter_async_context(server.running())
        yield RobotSide(middleware, server, sim)


async def wait_for_snapshots(server: RobotToolServer, *, names: Collection[str] | None = None,
                             timeout: float) -> None:
    """Wait (at most `timeout` s) until the snapshot tools `names` (default: all) have a value.

    A node's first message can go out before the server has subscribed to its topic (the
    subscription follows the node's announcement); a one-shot caller (``robovoice call``, a
    freshly started embedded robot) waits here instead of reading "no message received yet".
    """
    topics: set[str] = set()
    for entry in server.catalog.tools():
        if isinstance(entry, SnapshotEntry) and (names is None or entry.name in names):
            topics.add(entry.topic)
    pending = {t for t in topics if not _has_value(server.snapshots, t)}
    if not pending:
        return
    arrived = asyncio.Event()

    def receive(message: Message) -> None:
        pending.discard(message.topic)
        if not pending:
            arrived.set()

    subscriptions = [await server.middleware.subscribe(topic, receive) for topic in sorted(pending)]
    try:
        async with asyncio.timeout(timeout):
            await arrived.wait()
    except TimeoutError:
        log.info("no message yet on %s after %g s", ", ".join(sorted(pending)), timeout)
    finally:
        for subscription in subscriptions:
            subscription.close()


def _has_value(store: SnapshotStore, topic: str) -> bool:
    try:
        return store.read(topic, math.inf).has_value
    except UntrackedTopicError:
        return False


async def wait_for_tools(server: RobotToolServer, *, names: Collection[str] = (), timeout: float) -> None:
    """Wait (at most `timeout` s) until the tools `names` are offered, or, without names,
    until some tools are and the list has then been quiet for a moment (nodes on a network
    middleware announce themselves one by one). Returns either way: the caller reports."""
    quiet_s = 0.3

    def offered() -> set[str]:
        return {t.name for t in server.tools()}

    try:
        async with asyncio.timeout(timeout):
            if names:
                while not set(names) <= offered():
                    await server.changed()
                return
            while not offered():
                await server.changed()
            while True:
                await asyncio.wait_for(server.changed(), timeout=quiet_s)
    except TimeoutError:
        return
