"""Benchmarks of the MCP server (`bench_mcp`, shown by `robovoice bench mcp`).

- **Tool call latency**, p50/p95, in-process (the SDK's in-memory transport), over stdio
  (server in a child process) and over streamable HTTP on loopback (child process, uvicorn):
  robovoice's `RobotToolServer` calling an ``echo`` RPC of a node on the memory bus (schema
  validation, dispatch, audit log on), against a plain SDK server (`MCPServer`) offering the
  same ``echo`` tool, in the same run, in interleaved blocks so machine load hits both alike;
  the ratio of the two (goal: at most 1.2).
- **Transport floors**, timed in the same interleaved blocks (`bench_floor`): a minimal HTTP
  echo on the same server stack (uvicorn + Starlette, httpx2 client) and a raw loopback
  TCP round trip for HTTP, a bare pipe round trip for stdio; robovoice as a ratio of each
  (HTTP goals: p50 at most 3 ms and at most 2 x the HTTP echo, for both protocol versions).
- **Snapshot read vs no-op**: a snapshot tool (latest value from the `SnapshotStore`) against
  a no-op RPC tool on the same server (goal: within 1 ms; a snapshot never waits for a message).
- **Snapshot ingest**: a node publishes at 1 kHz and 10 kHz into a tracked topic while the
  snapshot tool is read; achieved rate, read latency, and memory before/after (tracemalloc and
  RSS: it must stay flat, the store keeps one value per topic).

The child processes are ``python -m robovoice.mcp_server.bench {robot|plain} {stdio|http}``.
"""

from __future__ import annotations

import asyncio
import contextlib
import gc
import os
import statistics
import sys
import tempfile
import time
import tracemalloc
from array import array
from collections.abc import AsyncIterator, Awaitable, Callable
from pathlib import Path
from typing import Any

import mcp_types as types
from mcp import Client
from mcp.client.stdio import StdioServerParameters
from mcp.server.mcpserver import MCPServer

from robovoice.mcp_server.audit import AuditLog
from robovoice.mcp_server.bench_floor import Call, net_floors, pipe_floor
from robovoice.mcp_server.server import RobotToolServer
from robovoice.middleware.base import JSON, NodeHost, NodeInfo, RpcInfo
from robovoice.middleware.memory import MemoryMiddleware

BLOCK = 25  # calls per interleaved block
WARMUP = 20
GOAL_RATIO = 1.2
GOAL_SNAPSHOT_MS = 1.0
GOAL_HTTP_MS = 3.0
GOAL_FLOOR_RATIO = 2.0  # robovoice over HTTP vs the minimal HTTP echo, p50
INGEST_RATES_HZ = (1_000, 10_000)
INGEST_SECONDS = 2.0
STATE = {"x": 2.25, "y": 6.5, "heading_deg": 90.0, "nearest_place": "kitchen", "moving": False}

BENCH_MANIFEST: dict[str, JSON] = {
    "node": "bench",
    "tools": [
        {"name": "echo", "rpc": "echo", "description": "Echo the text back.",
         "parameters": {"type": "object", "properties": {"text": {"type": "string"}}, "required": ["text"]}},
        {"name": "noop", "rpc": "noop", "description": "Do nothing."},
    ],
    "snapshots": [
        {"name": "get_state", "topic": "bench/state", "description": "The latest state.", "max_age_s": 3600},
    ],
}


# --- the two servers ------------------------------------------------------------------------


async def _echo(args: dict[str, JSON]) -> JSON:
    return {"echo": args["text"]}


async def _noop(args: dict[str, JSON]) -> JSON:
    return {}


async def host_bench_node(middleware: MemoryMiddleware) -> NodeHost:
    info = NodeInfo("bench", rpcs=(RpcInfo("echo", params=("text",)), RpcInfo("noop")), topics=("bench/state",),
                    manifest=BENCH_MANIFEST, manifest_source="<bench node>")
    return await middleware.host(info, {"echo": _echo, "noop": _noop}, {})


@contextlib.asynccontextmanager
async def robot_server(audit_dir: Path) -> AsyncIterator[tuple[RobotToolServer, NodeHost]]:
    """A `RobotToolServer` over the bench node, audit log on (as in production)."""
    middleware = MemoryMiddleware()
    await middleware.start()
    audit = AuditLog(audit_dir / f"audit-{os.getpid()}.jsonl")
    server = RobotToolServer(middleware, audit=audit)
    try:
        async with server.running():
            host = await host_bench_node(middleware)
            await server.settled()
            host.publish("bench/state", STATE)
            yield server, host
    finally:
        audit.close()
        await middleware.close()


def plain_server() -> MCPServer:
    """The plain SDK server with the equivalent tools."""
    mcp = MCPServer("plain", log_level="WARNING")  # its constructor configures logging when nobody has

    @mcp.tool()
    def echo(text: str) -> dict[str, str]:
        """Echo the text back."""
        return {"echo": text}

    @mcp.tool()
    def noop() -> dict[str, str]:
        """Do nothing."""
        return {}

    return mcp


# --- measuring ------------------------------------------------------------------------------


def _stats(samples_ms: list[float]) -> dict[str, float]:
    ordered = sorted(samples_ms)
    return {
        "p50": round(statistics.median(ordered), 3),
        "p95": round(ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))], 3),
        "mean": round(statistics.fmean(ordered), 3),
        "n": len(ordered),
    }


async def _timed(call: Call, samples: list[float]) -> None:
    start = time.perf_counter()
    result = await call()
    samples.append((time.perf_counter() - start) * 1000.0)
    if isinstance(result, types.CallToolResult) and result.is_error:
        raise RuntimeError(f"benchmark call failed: {result.content}")


async def _interleaved(calls: dict[str, Call], n: int) -> dict[str, dict[str, float]]:
    samples: dict[str, list[float]] = {name: [] for name in calls}
    for call in calls.values():
        for _ in range(min(WARMUP, n)):
            await call()
    while min(len(s) for s in samples.values()) < n:
        for name, call in calls.items():
            for _ in range(min(BLOCK, n - len(samples[name]))):
                await _timed(call, samples[name])
    return {name: _stats(s) for name, s in samples.items()}


def _compare(stats: dict[str, dict[str, float]]) -> dict[str, Any]:
    robot, plain = stats["robot"], stats["plain"]
    return {"robot": robot, "plain": plain,
            "ratio_p50": round(robot["p50"] / plain["p50"], 3), "ratio_p95": round(robot["p95"] / plain["p95"], 3)}


def _floors(stats: dict[str, dict[str, float]], names: tuple[str, ...]) -> dict[str, Any]:
    """Each floor's stats, and robovoice's p50 as a multiple of it."""
    robot = stats["robot"]["p50"]
    return {name: {**stats[name], "robot_ratio_p50": round(robot / stats[name]["p50"], 3)} for name in names}


def _echo_call(client: Client) -> Callable[[], Awaitable[types.CallToolResult]]:
    return lambda: client.call_tool("echo", {"text": "hello robot"})


async def _bench_inprocess(n: int, audit_dir: Path) -> dict[str, Any]:
    async with robot_server(audit_dir) as (server, _), \
            Client(server.server, mode="legacy", cache=None) as robot, \
            Client(plain_server(), mode="legacy", cache=None) as plain:
        stats = await _interleaved({"robot": _echo_call(robot), "plain": _echo_call(plain)}, n)
        snap = await _interleaved({"snapshot": lambda: robot.call_tool("get_state", {}),
                                   "noop": lambda: robot.call_tool("noop", {})}, n)
    return {"echo": _compare(stats), "snapshot_vs_noop": _snapshot_verdict(snap)}


def _snapshot_verdict(stats: dict[str, dict[str, float]]) -> dict[str, Any]:
    diff = stats["snapshot"]["p50"] - stats["noop"]["p50"]
    return {**stats, "diff_p50_ms": round(diff, 3), "within_goal": diff <= GOAL_SNAPSHOT_MS}


def _child(kind: str, transport: str) -> list[str]:
    return [sys.executable, "-m", "robovoice.mcp_server.bench", kind, transport]


async def _bench_stdio(n: int) -> dict[str, Any]:
    async with Client(StdioServerParameters(command=sys.executable, args=_child("robot", "stdio")[1:]),
                      mode="legacy", cache=None) as robot, \
            Client(StdioServerParameters(command=sys.executable, args=_child("plain", "stdio")[1:]),
                   mode="legacy", cache=None) as plain, \
            pipe_floor() as pipe:
        stats = await _interleaved({"robot": _echo_call(robot), "plain": _echo_call(plain), "pipe": pipe}, n)
    return {"echo": _compare(stats), "floor": _floors(stats, ("pipe",))}


@contextlib.asynccontextmanager
async def _http_child(kind: str) -> AsyncIterator[str]:
    process = await asyncio.create_subprocess_exec(*_child(kind, "http"), stdout=asyncio.subprocess.PIPE,
                                                   stderr=asyncio.subprocess.DEVNULL)
    try:
        assert process.stdout is not None
        async with asyncio.timeout(60):
            line = (await process.stdout.readline()).decode().strip()
        if not line.startswith("ready "):
            raise RuntimeError(f"the {kind} HTTP server did not start: {line!r}")
        yield line.split()[1]
    finally:
        if process.returncode is None:
            process.terminate()
            await process.wait()


async def _bench_http(n: int) -> dict[str, dict[str, Any]]:
    """Both servers and the floors in child processes; a 2025 session (``legacy``) and a
    2026-07-28 (``auto``) client each."""
    out: dict[str, dict[str, Any]] = {}
    async with _http_child("robot") as robot_url, _http_child("plain") as plain_url, net_floors() as floors:
        for mode in ("legacy", "auto"):
            async with Client(robot_url, mode=mode, cache=None) as robot, \
                    Client(plain_url, mode=mode, cache=None) as plain:
                stats = await _interleaved({"robot": _echo_call(robot), "plain": _echo_call(plain), **floors}, n)
                snap = await _interleaved({"snapshot": lambda: robot.call_tool("get_state", {}),
                                           "noop": lambda: robot.call_tool("noop", {})}, n)
            floor = _floors(stats, ("http_echo", "tcp"))
            robot_p50 = stats["robot"]["p50"]
            goals = {"p50_within_ms": robot_p50 <= GOAL_HTTP_MS,
                     "within_floor_ratio": floor["http_echo"]["robot_ratio_p50"] <= GOAL_FLOOR_RATIO}
            out[mode] = {"echo": _compare(stats), "floor": floor, "goals": goals,
                         "snapshot_vs_noop": _snapshot_verdict(snap)}
    return out


def _rss_kb() -> int:
    with open("/proc/self/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


async def _bench_ingest(audit_dir: Path, seconds: float) -> list[dict[str, Any]]:
    """Publish at each rate for a while; read the snapshot tool meanwhile; memory before/after."""
    out: list[dict[str, Any]] = []
    async with robot_server(audit_dir) as (server, host):
        for rate in INGEST_RATES_HZ:
            for warm in (True, False):  # a first pass warms caches and allocators
                gc.collect()
                tracemalloc.start()
                traced_before = tracemalloc.get_traced_memory()[0]
                rss_before = _rss_kb()
                published, read_ms = await _publish_and_read(server, host, rate, 0.3 if warm else seconds)
                gc.collect()
                traced_after = tracemalloc.get_traced_memory()[0]
                rss_after = _rss_kb()
                tracemalloc.stop()
                if warm:
                    continue
                out.append({
                    "rate_hz": rate, "seconds": seconds, "published": published,
                    "achieved_hz": round(published / seconds), "read_ms": read_ms,
                    "tracemalloc_growth_kb": round((traced_after - traced_before) / 1024, 1),
                    "rss_before_kb": rss_before, "rss_after_kb": rss_after,
                })
    return out


async def _publish_and_read(server: RobotToolServer, host: NodeHost, rate: int,
                            seconds: float) -> tuple[int, dict[str, float]]:
    """Publish at `rate` for `seconds`, reading the snapshot tool about once a millisecond.
    The read timings go into a preallocated array, so they do not count as growth."""
    loop = asyncio.get_running_loop()
    start = loop.time()
    published = 0
    reads = array("d", bytes(8 * int(seconds * 2000 + 100)))
    count = 0
    tick = 0.001
    while (now := loop.time()) - start < seconds:
        due = int((now - start) * rate) + 1
        while published < due:
            host.publish("bench/state", {**STATE, "seq": published})
            published += 1
        t0 = time.perf_counter()
        result = await server.call_tool("get_state", {})
        if count < len(reads):
            reads[count] = (time.perf_counter() - t0) * 1000.0
            count += 1
        if result.is_error:
            raise RuntimeError("snapshot read failed")
        await asyncio.sleep(tick)
    return published, _stats(list(reads[:count]))


async def bench_mcp(n: int = 200, *, ingest_seconds: float = INGEST_SECONDS) -> dict[str, Any]:
    """Run every MCP benchmark; `n` calls per measured series, `ingest_seconds` per ingest
    rate. Returns plain numbers (`format_report` makes text of them)."""
    if n < 10:
        raise ValueError("n must be at least 10")
    with tempfile.TemporaryDirectory(prefix="robovoice-bench-") as tmp:
        audit_dir = Path(tmp)
        report: dict[str, Any] = {"n": n, "block": BLOCK, "goal_ratio": GOAL_RATIO,
                                  "goal_snapshot_ms": GOAL_SNAPSHOT_MS, "goal_http_ms": GOAL_HTTP_MS,
                                  "goal_floor_ratio": GOAL_FLOOR_RATIO}
        report["inprocess"] = await _bench_inprocess(n, audit_dir)
        report["stdio"] = await _bench_stdio(n)
        http = await _bench_http(n)
        report["http"], report["http_2026"] = http["legacy"], http["auto"]
        report["ingest"] = await _bench_ingest(audit_dir, ingest_seconds)
    return report


def format_report(report: dict[str, Any]) -> str:
    """The report as a few readable lines."""
    lines = [f"MCP tool call latency, ms ({report['n']} calls per series, interleaved blocks of {report['block']}); "
             f"robovoice (RobotToolServer, audit on) vs a plain SDK MCPServer with the same tool; "
             f"goal ratio <= {report['goal_ratio']}"]
    labels = {"inprocess": "in-process (memory transport)", "stdio": "stdio (child process)",
              "http": "streamable HTTP, 2025-11-25 session", "http_2026": "streamable HTTP, 2026-07-28"}
    for key, label in labels.items():
        echo = report[key]["echo"]
        r, p = echo["robot"], echo["plain"]
        lines.append(f"  {label:<38} robovoice p50 {r['p50']:7.3f} p95 {r['p95']:7.3f} | plain p50 {p['p50']:7.3f} "
                     f"p95 {p['p95']:7.3f} | ratio p50 {echo['ratio_p50']:.2f} p95 {echo['ratio_p95']:.2f}")
    lines.append(f"Transport floors, ms, same run and blocks (HTTP goals: robovoice p50 <= "
                 f"{report['goal_http_ms']:g} ms and <= {report['goal_floor_ratio']:g} x the HTTP echo)")
    floor_labels = {"http_echo": "HTTP echo (uvicorn+Starlette, httpx2)", "tcp": "raw TCP round trip",
                    "pipe": "bare pipe round trip"}
    for key in ("stdio", "http", "http_2026"):
        for name, floor in report[key]["floor"].items():
            lines.append(f"  {labels[key]:<38} {floor_labels[name]:<38} p50 {floor['p50']:7.3f} "
                         f"p95 {floor['p95']:7.3f} | robovoice / floor p50 {floor['robot_ratio_p50']:.2f}")
        if "goals" in report[key]:
            goals = report[key]["goals"]
            verdict = "OK" if all(goals.values()) else "NOT MET: " + ", ".join(k for k, v in goals.items() if not v)
            lines.append(f"  {labels[key]:<38} goals: {verdict}")
    lines.append(f"Snapshot tool vs no-op tool, ms (goal: p50 within {report['goal_snapshot_ms']} ms)")
    for key in ("inprocess", "http", "http_2026"):
        snap = report[key]["snapshot_vs_noop"]
        lines.append(f"  {labels[key]:<38} snapshot p50 {snap['snapshot']['p50']:7.3f} p95 "
                     f"{snap['snapshot']['p95']:7.3f} | no-op p50 {snap['noop']['p50']:7.3f} p95 "
                     f"{snap['noop']['p95']:7.3f} | diff {snap['diff_p50_ms']:+.3f} "
                     f"{'OK' if snap['within_goal'] else 'over goal'}")
    lines.append("Snapshot ingest (publish into a tracked topic while reading the snapshot tool)")
    for row in report["ingest"]:
        lines.append(f"  {row['rate_hz']:>6} Hz for {row['seconds']:g} s: {row['published']} messages "
                     f"({row['achieved_hz']} Hz), read p50 {row['read_ms']['p50']:.3f} ms p95 "
                     f"{row['read_ms']['p95']:.3f} ms, tracemalloc growth {row['tracemalloc_growth_kb']:+.1f} kB, "
                     f"RSS {row['rss_before_kb']} -> {row['rss_after_kb']} kB")
    return "\n".join(lines)


# --- the child processes --------------------------------------------------------------------


async def _serve_child(kind: str, transport: str) -> None:
    from robovoice.mcp_server.http import asgi_server, http_server
    from robovoice.mcp_server.stdio import serve_stdio

    if kind == "plain":
        plain = plain_server()
        if transport == "stdio":
            await plain.run_stdio_async()
            return
        async with asgi_server(plain.streamable_http_app(), host="127.0.0.1", port=0) as endpoint:
            print(f"ready {endpoint.url}", flush=True)
            await asyncio.Event().wait()
    with tempfile.TemporaryDirectory(prefix="robovoice-bench-") as tmp:
        async with robot_server(Path(tmp)) as (server, _):
            if transport == "stdio":
                await serve_stdio(server)
                return
            async with http_server(server, port=0) as endpoint:
                print(f"ready {endpoint.url}", flush=True)
                await asyncio.Event().wait()


if __name__ == "__main__":
    import logging

    logging.basicConfig(level=logging.ERROR, stream=sys.stderr)
    with contextlib.suppress(KeyboardInterrupt):
        asyncio.run(_serve_child(sys.argv[1], sys.argv[2]))
