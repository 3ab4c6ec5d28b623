"""Load on the robot side (`bench_load`, shown by `robovoice bench load`).

N concurrent MCP clients (the SDK's `Client`, 2025 handshake, each with its GET stream open
for notifications) over streamable HTTP to one `RobotToolServer` under uvicorn on loopback,
each making a fixed number of calls — tools and snapshots, stable and churning — while sim
nodes join and leave (the ``projector`` and ``communication`` nodes are started and stopped as
separate sim robots every `churn_s`), on the memory bus or over Zenoh (`middleware`). Every
call is bounded by `call_timeout_s`.

Reported: throughput, latency p50/p99/max, errors (exceptions, protocol errors, timeouts,
tool errors other than the expected ones) vs expected refusals (a tool of a node that has
just left: ``unknown_tool`` / ``node_unavailable``), how many node joins/leaves happened,
whether a final ``tools/list_changed`` reached every client, and whether the audit log holds
one valid line per completed call. Clients and server share this process (and its cores).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import resource
import socket
import statistics
import tempfile
import time
from collections.abc import AsyncIterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import mcp_types as types
from mcp import Client

from robovoice.address import MiddlewareAddress, SimAddress
from robovoice.mcp_server.audit import read_audit
from robovoice.mcp_server.http import http_server
from robovoice.mcp_server.runtime import RobotSide, open_robot_side
from robovoice.middleware import open_middleware
from robovoice.middleware.base import Middleware
from robovoice.sim.robot import SimRobot, start_sim_robot

STABLE_NODES = ("navigation", "base", "localization", "camera")
CHURNING_NODES = ("projector", "communication")
EXPECTED_REFUSALS = frozenset({"unknown_tool", "node_unavailable"})
# (tool, arguments): snapshots and RPCs on stable nodes, RPCs on the churning ones
CALL_MIX: tuple[tuple[str, dict[str, Any]], ...] = (
    ("get_battery_state", {}),
    ("get_robot_pose", {}),
    ("get_navigation_targets", {}),
    ("list_contacts", {}),
    ("get_projector_state", {}),
    ("set_projector_power", {"on": True}),
    ("get_battery_state", {}),
    ("get_call_state", {}),
)


@dataclass
class _ClientStats:
    latencies_ms: list[float] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    refusals: int = 0
    timeouts: int = 0
    list_changed: int = 0


@dataclass(frozen=True, slots=True)
class LoadReport:
    middleware: str
    clients: int
    calls_per_client: int
    calls_done: int
    errors: int
    timeouts: int
    expected_refusals: int
    seconds: float
    calls_per_s: float
    p50_ms: float
    p99_ms: float
    max_ms: float
    node_joins: int
    node_leaves: int
    list_changed_min_per_client: int
    final_list_changed_reached: int
    audit_lines: int
    audit_skipped_lines: int
    cpu_s: float
    max_rss_mib: float
    first_errors: list[str]

    @property
    def ok(self) -> bool:
        return (self.errors == 0 and self.timeouts == 0 and self.calls_done == self.clients * self.calls_per_client
                and self.final_list_changed_reached == self.clients and self.audit_lines == self.calls_done
                and self.audit_skipped_lines == 0)

    def to_dict(self) -> dict[str, Any]:
        from dataclasses import asdict

        return {**asdict(self), "ok": self.ok}


class _Churn:
    """Starts and stops the churning sim nodes on `middleware`."""

    def __init__(self, middleware: Middleware, speed: float) -> None:
        self._middleware = middleware
        self._speed = speed
        self._robot: SimRobot | None = None
        self.joins = 0
        self.leaves = 0

    async def join(self) -> None:
        if self._robot is None:
            self._robot = await start_sim_robot(self._middleware, speed=self._speed, nodes=CHURNING_NODES)
            self.joins += 1

    async def leave(self) -> None:
        if self._robot is not None:
            robot, self._robot = self._robot, None
            await robot.stop()
            self.leaves += 1

    async def run(self, every_s: float, stop: asyncio.Event) -> None:
        while not stop.is_set():
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(stop.wait(), every_s)
            if stop.is_set():
                break
            await (self.leave() if self._robot is not None else self.join())


async def _one_client(url: str, index: int, calls: int, call_timeout_s: float, stats: _ClientStats,
                      ready: asyncio.Barrier, go: asyncio.Event, done: asyncio.Event,
                      finished: asyncio.Queue[int]) -> None:
    async def on_message(message: Any) -> None:
        if isinstance(message, types.ToolListChangedNotification):
            stats.list_changed += 1

    try:
        async with Client(url, mode="legacy", message_handler=on_message) as client:
            await client.list_tools()
            await ready.wait()
            await go.wait()
            for n in range(calls):
                tool, arguments = CALL_MIX[(index + n) % len(CALL_MIX)]
                t0 = time.perf_counter()
                try:
                    async with asyncio.timeout(call_timeout_s):
                        result = await client.call_tool(tool, arguments)
                except TimeoutError:
                    stats.timeouts += 1
                    continue
                except Exception as exc:  # a protocol error: counted, and the client goes on
                    stats.errors.append(f"{tool}: {type(exc).__name__}: {exc}")
                    continue
                stats.latencies_ms.append((time.perf_counter() - t0) * 1000.0)
                if result.is_error:
                    code = _error_code(result)
                    if code in EXPECTED_REFUSALS:
                        stats.refusals += 1
                    else:
                        stats.errors.append(f"{tool}: tool error {code}")
            finished.put_nowait(index)
            await done.wait()  # stay connected for the final list change
    except Exception as exc:
        stats.errors.append(f"client {index}: {type(exc).__name__}: {exc}")
        if not go.is_set():
            with contextlib.suppress(Exception):
                await ready.wait()
        finished.put_nowait(index)


def _error_code(result: types.CallToolResult) -> str:
    text = next((b.text for b in result.content if isinstance(b, types.TextContent)), "{}")
    try:
        return str(json.loads(text).get("error"))
    except (ValueError, AttributeError):
        return "?"


@contextlib.asynccontextmanager
async def _temporary_audit() -> AsyncIterator[Path]:
    with tempfile.TemporaryDirectory(prefix="robovoice-load-") as folder:
        yield Path(folder) / "audit.jsonl"


@contextlib.asynccontextmanager
async def _robot(middleware: str, sim_speed: float, audit_path: Path,
                 ros_domain: int) -> AsyncIterator[tuple[RobotSide, Middleware]]:
    """The robot side and the middleware the churning nodes go on: ``memory`` (the sim in this
    process), ``zenoh`` (a fresh loopback rendezvous) or ``ros2`` (ROS_DOMAIN_ID `ros_domain`,
    loopback discovery): the stable nodes and the churning ones on two more sessions in this
    process, so every call and presence change crosses the network middleware."""
    if middleware == "memory":
        async with open_robot_side(SimAddress(speed=sim_speed, nodes=STABLE_NODES), manifests=None,
                                   audit_log=audit_path) as side:
            yield side, side.middleware
        return
    uri = _network_uri(middleware, ros_domain)
    nodes, churning = open_middleware(uri), open_middleware(uri)
    await nodes.start()
    await churning.start()
    stable = await start_sim_robot(nodes, speed=sim_speed, nodes=STABLE_NODES)
    try:
        async with open_robot_side(MiddlewareAddress(uri), manifests=None, audit_log=audit_path) as side:
            async with asyncio.timeout(30):
                while "navigate_to" not in {t.name for t in side.server.tools()}:
                    await side.server.changed()
            yield side, churning
    finally:
        await stable.stop()
        await churning.close()
        await nodes.close()


def _network_uri(middleware: str, ros_domain: int) -> str:
    if middleware == "ros2":
        return f"ros2://?domain_id={ros_domain}"
    if middleware != "zenoh":
        raise ValueError(f"middleware {middleware!r}: use memory, zenoh or ros2")
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    return f"zenoh://127.0.0.1:{port}?robot=load"


async def bench_load(clients: int = 50, calls: int = 200, *, churn_s: float = 0.5, call_timeout_s: float = 30.0,
                     sim_speed: float = 20.0, middleware: str = "memory", ros_domain: int = 120) -> LoadReport:
    """Run the load (see the module docstring) and report."""
    cpu0 = time.process_time()
    async with (_temporary_audit() as audit_path,
                _robot(middleware, sim_speed, audit_path, ros_domain) as (side, churn_on),
                http_server(side.server, port=0) as endpoint):
        churn = _Churn(churn_on, sim_speed)
        await churn.join()
        async with asyncio.timeout(30):
            while "set_projector_power" not in {t.name for t in side.server.tools()}:
                await side.server.changed()
        await side.server.settled()
        stats = [_ClientStats() for _ in range(clients)]
        ready, go, done, stop = asyncio.Barrier(clients + 1), asyncio.Event(), asyncio.Event(), asyncio.Event()
        finished: asyncio.Queue[int] = asyncio.Queue()
        tasks = [asyncio.create_task(_one_client(endpoint.url, i, calls, call_timeout_s, stats[i], ready, go, done,
                                                 finished))
                 for i in range(clients)]
        async with asyncio.timeout(120):
            await ready.wait()
        churner = asyncio.create_task(churn.run(churn_s, stop))
        t0 = time.perf_counter()
        go.set()
        for _ in range(clients):  # each client bounds each call: this ends
            await finished.get()
        seconds = time.perf_counter() - t0
        stop.set()
        await churner
        # a final change must reach every client
        before = [s.list_changed for s in stats]
        await (churn.leave() if churn.joins > churn.leaves else churn.join())
        with contextlib.suppress(TimeoutError):
            async with asyncio.timeout(15):
                while any(s.list_changed <= b for s, b in zip(stats, before, strict=True)):
                    await asyncio.sleep(0.05)
        reached = sum(s.list_changed > b for s, b in zip(stats, before, strict=True))
        done.set()
        async with asyncio.timeout(60):
            await asyncio.gather(*tasks)
        await churn.leave()
        reading = read_audit(audit_path)
    latencies = sorted(x for s in stats for x in s.latencies_ms)
    errors = [e for s in stats for e in s.errors]
    done_calls = len(latencies)
    quantiles = statistics.quantiles(latencies, n=100, method="inclusive") if len(latencies) > 1 else latencies * 99
    return LoadReport(
        middleware=middleware, clients=clients, calls_per_client=calls, calls_done=done_calls, errors=len(errors),
        timeouts=sum(s.timeouts for s in stats), expected_refusals=sum(s.refusals for s in stats),
        seconds=round(seconds, 2), calls_per_s=round(done_calls / seconds, 1) if seconds else 0.0,
        p50_ms=round(quantiles[49], 2) if quantiles else 0.0, p99_ms=round(quantiles[98], 2) if quantiles else 0.0,
        max_ms=round(latencies[-1], 2) if latencies else 0.0, node_joins=churn.joins, node_leaves=churn.leaves,
        list_changed_min_per_client=min((s.list_changed for s in stats), default=0),
        final_list_changed_reached=reached, audit_lines=len(reading.records),
        audit_skipped_lines=len(reading.skipped), cpu_s=round(time.process_time() - cpu0, 1),
        max_rss_mib=round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
        first_errors=errors[:10],
    )
