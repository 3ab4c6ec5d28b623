"""Benchmarks of the Zenoh adapter, with the nodes in another process (`run_zenoh_bench`).

- **RPC round trip**: `ZenohMiddleware.call` to an echo RPC, next to a bare blocking
  ``session.get()`` against a raw queryable in the same child process (the anchor), in
  interleaved blocks so machine load hits both alike; median, p95, their ratio and the
  difference of medians (goal: at most `GOAL_OVER_BARE_MS`).
- **MCP tool call**: ``get_navigation_targets`` through the MCP server (SDK client over the
  in-memory transport) with the navigation node over Zenoh in another process, against the
  same with the sim in-process on the memory bus; interleaved, same run, ratio of medians.
- **Snapshot ingest**: a node in another process publishes pose messages as fast as it can;
  this process keeps them in a `SnapshotStore` (as the MCP server does). Messages per
  second received, how many arrived, and the resident memory before and after two bursts
  (it must stay flat: the store keeps the latest value, the adapter's backlog is bounded).

Returns numbers only (`ZenohBenchReport`); the CLI formats them. The child processes are
``python -m robovoice.middleware.bench_zenoh {rpc|pub} PORT``.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import subprocess
import sys
import time
from collections.abc import AsyncIterator, Awaitable, Callable
from dataclasses import asdict, dataclass

import zenoh

from robovoice.middleware.base import JSON, Message, NodeInfo, RpcInfo
from robovoice.middleware.bench_stats import BLOCK, Stats
from robovoice.middleware.zenoh import ZenohMiddleware
from robovoice.middleware.zenoh_bridge import close_session
from robovoice.snapshot.store import SnapshotStore

RAW_KEY = "robovoice-bench/ping"
GOAL_OVER_BARE_MS = 0.25  # an RPC's median may exceed the bare get's by this much
POSE = {"x": 2.25, "y": 6.5, "heading": 1.57, "nearest_place": "kitchen", "moving": True}




@dataclass(frozen=True, slots=True)
class IngestResult:
    sent: int
    received: int
    per_second: float
    rss_before_kib: int
    rss_after_first_kib: int
    rss_after_second_kib: int


@dataclass(frozen=True, slots=True)
class ZenohBenchReport:
    bare_get: Stats
    rpc: Stats
    rpc_ratio: float  # rpc median / bare get median
    rpc_over_bare_ms: float  # rpc median - bare get median
    rpc_within_goal: bool  # rpc_over_bare_ms <= GOAL_OVER_BARE_MS
    mcp_memory: Stats | None
    mcp_zenoh: Stats | None
    mcp_ratio: float | None  # zenoh median / memory median
    ingest: IngestResult | None

    def to_dict(self) -> dict[str, object]:
        return asdict(self)


# --- orchestration -------------------------------------------------------------------------


async def run_zenoh_bench(*, calls: int = 1000, mcp_calls: int = 300, ingest_messages: int = 20000,
                          mcp: bool = True, ingest: bool = True) -> ZenohBenchReport:
    """Run the benchmarks (see the module docstring) on loopback ports chosen here."""
    bare, rpc = await _bench_rpc(calls)
    mcp_memory = mcp_zenoh = None
    if mcp:
        mcp_memory, mcp_zenoh = await _bench_mcp(mcp_calls)
    ingest_result = await _bench_ingest(ingest_messages) if ingest else None
    return ZenohBenchReport(
        bare_get=bare, rpc=rpc, rpc_ratio=rpc.median_ms / bare.median_ms,
        rpc_over_bare_ms=rpc.median_ms - bare.median_ms,
        rpc_within_goal=rpc.median_ms - bare.median_ms <= GOAL_OVER_BARE_MS,
        mcp_memory=mcp_memory, mcp_zenoh=mcp_zenoh,
        mcp_ratio=None if mcp_memory is None or mcp_zenoh is None else mcp_zenoh.median_ms / mcp_memory.median_ms,
        ingest=ingest_result,
    )


def _free_port() -> int:
    import socket

    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@contextlib.asynccontextmanager
async def _child(argv: list[str], ready: str) -> AsyncIterator[subprocess.Popen[str]]:
    """A child process, up once it prints `ready`; always terminated on the way out."""
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, text=True, env=dict(os.environ, PYTHONUNBUFFERED="1"))
    try:
        assert proc.stdout is not None
        line = await asyncio.wait_for(asyncio.to_thread(proc.stdout.readline), 30)
        if ready not in line:
            raise RuntimeError(f"benchmark child {argv} did not start (said {line!r})")
        yield proc
    finally:
        proc.terminate()
        try:
            await asyncio.to_thread(proc.wait, 5)
        except subprocess.TimeoutExpired:
            proc.kill()
            await asyncio.to_thread(proc.wait, 5)
        if proc.stdout is not None:
            proc.stdout.close()


async def _interleaved(rounds: int, *runs: Callable[[], Awaitable[float]]) -> list[list[float]]:
    samples: list[list[float]] = [[] for _ in runs]
    for _ in range(rounds):
        for run, into in zip(runs, samples, strict=True):
            for _ in range(BLOCK):
                into.append(await run())
    return samples


async def _until(condition: Callable[[], bool], bound: float = 10.0) -> None:
    async with asyncio.timeout(bound):
        while not condition():
            await asyncio.sleep(0.01)


async def _bench_rpc(calls: int) -> tuple[Stats, Stats]:
    port = _free_port()
    argv = [sys.executable, "-m", "robovoice.middleware.bench_zenoh", "rpc", str(port)]
    async with _child(argv, "ready"):
        client = ZenohMiddleware.from_uri(f"zenoh://?connect=tcp/127.0.0.1:{port}&robot=bench")
        await client.start()
        config = zenoh.Config()
        config.insert_json5("scouting/multicast/enabled", "false")
        config.insert_json5("connect/endpoints", json.dumps([f"tcp/127.0.0.1:{port}"]))
        raw = await asyncio.to_thread(zenoh.open, config)
        try:
            await _until(lambda: "echo" in client.nodes())
            # the raw queryable lives on the child's second session: wait until the mesh reaches it
            await _until(lambda: any(r.ok is not None for r in raw.get(RAW_KEY, payload=b"0", timeout=1)))
            counter = iter(range(10**9))

            async def bare() -> float:  # blocking, like the anchor measurement
                start = time.perf_counter()
                replies = list(raw.get(RAW_KEY, payload=str(next(counter))))
                elapsed = time.perf_counter() - start
                if len(replies) != 1 or replies[0].ok is None:
                    raise RuntimeError("the bare queryable did not answer")
                return elapsed

            async def rpc() -> float:
                i = next(counter)
                start = time.perf_counter()
                result = await client.call("echo", "echo", {"i": i}, timeout=5)
                elapsed = time.perf_counter() - start
                if result != {"i": i}:
                    raise RuntimeError(f"echo answered {result!r}")
                return elapsed

            await _interleaved(2, bare, rpc)  # warm-up
            bare_s, rpc_s = await _interleaved(max(1, calls // BLOCK), bare, rpc)
        finally:
            close_session(raw)
            await client.close()
    return Stats.of(bare_s), Stats.of(rpc_s)


async def _bench_mcp(calls: int) -> tuple[Stats, Stats]:
    import mcp_types as types
    from mcp import Client

    from robovoice.address import MiddlewareAddress, SimAddress
    from robovoice.mcp_server import open_robot_side, wait_for_tools

    port = _free_port()
    uri = f"zenoh://127.0.0.1:{port}?robot=bench-mcp"
    argv = [sys.executable, "-m", "robovoice.cli", "sim", "--middleware", uri, "--node", "navigation"]
    tool = "get_navigation_targets"
    info = types.Implementation(name="robovoice-bench", version="bench")
    async with (
        open_robot_side(MiddlewareAddress(uri), manifests=None, audit_log=None) as over_zenoh,
        _child(argv, "ready"),
        open_robot_side(SimAddress(nodes=("navigation",)), manifests=None, audit_log=None) as in_memory,
    ):
        await wait_for_tools(over_zenoh.server, names=[tool], timeout=10)
        async with (
            Client(in_memory.server.server, mode="legacy", cache=None, client_info=info) as memory_client,
            Client(over_zenoh.server.server, mode="legacy", cache=None, client_info=info) as zenoh_client,
        ):
            def timed(client: Client) -> Callable[[], Awaitable[float]]:
                async def call() -> float:
                    start = time.perf_counter()
                    result = await client.call_tool(tool, {})
                    elapsed = time.perf_counter() - start
                    if result.is_error:
                        raise RuntimeError(f"{tool} failed: {result.content}")
                    return elapsed

                return call

            await _interleaved(1, timed(memory_client), timed(zenoh_client))  # warm-up
            memory_s, zenoh_s = await _interleaved(max(1, calls // BLOCK), timed(memory_client),
                                                   timed(zenoh_client))
    return Stats.of(memory_s), Stats.of(zenoh_s)


def _rss_kib() -> int:
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") // 1024


async def _bench_ingest(messages: int) -> IngestResult:
    port = _free_port()
    client = ZenohMiddleware.from_uri(f"zenoh://?listen=tcp/127.0.0.1:{port}&robot=bench")
    await client.start()
    try:
        argv = [sys.executable, "-m", "robovoice.middleware.bench_zenoh", "pub", str(port)]
        async with _child(argv, "ready"):
            await _until(lambda: "pub" in client.nodes())
            store = SnapshotStore()
            await store.track(client, "bench/pose")
            times: list[float] = []

            def count(message: Message) -> None:
                if isinstance(message.value, dict) and "seq" in message.value:
                    times.append(time.perf_counter())

            await client.subscribe("bench/pose", count)
            # the subscription must reach the publisher: ask for warm-up messages until one lands
            async with asyncio.timeout(10):
                while store.read("bench/pose", 60).reason is not None:
                    await client.call("pub", "burst", {"n": 1}, timeout=5)
            times.clear()
            rss_before = _rss_kib()
            rss_after: list[int] = []
            for _ in range(2):
                times.clear()
                await client.call("pub", "burst", {"n": messages}, timeout=120)
                await _settle(times)
                rss_after.append(_rss_kib())
            received = len(times)
            span = times[-1] - times[0] if len(times) > 1 else float("nan")
            store.close()
    finally:
        await client.close()
    return IngestResult(messages, received, (received - 1) / span, rss_before, rss_after[0], rss_after[1])


async def _settle(times: list[float], quiet_s: float = 0.5) -> None:
    """Return once no message has arrived for `quiet_s`."""
    seen = -1
    while len(times) != seen:
        seen = len(times)
        await asyncio.sleep(quiet_s)


# --- child processes -------------------------------------------------------------------------


async def _serve_rpc(port: int) -> None:
    node = ZenohMiddleware.from_uri(f"zenoh://?listen=tcp/127.0.0.1:{port}&robot=bench")
    await node.start()
    config = zenoh.Config()
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("connect/endpoints", json.dumps([f"tcp/127.0.0.1:{port}"]))
    raw = zenoh.open(config)

    def ping(query: zenoh.Query) -> None:
        with query:
            query.reply(RAW_KEY, query.payload.to_bytes() if query.payload else b"")

    async def echo(args: dict[str, JSON]) -> JSON:
        return args

    queryable = raw.declare_queryable(RAW_KEY, ping)
    await node.host(NodeInfo("echo", rpcs=(RpcInfo("echo"),)), {"echo": echo}, {})
    await _wait_forever("ready")
    del queryable
    close_session(raw)
    await node.close()


async def _serve_pub(port: int) -> None:
    node = ZenohMiddleware.from_uri(f"zenoh://?connect=tcp/127.0.0.1:{port}&robot=bench")
    await node.start()
    seq = 0

    async def burst(args: dict[str, JSON]) -> JSON:
        nonlocal seq
        n = args["n"]
        assert isinstance(n, int)
        for _ in range(n):
            seq += 1
            host.publish("bench/pose", {**POSE, "seq": seq})
        return {"sent": n}

    host = await node.host(NodeInfo("pub", rpcs=(RpcInfo("burst", params=("n",)),), topics=("bench/pose",)),
                           {"burst": burst}, {})
    await _wait_forever("ready")
    await node.close()


async def _wait_forever(ready: str) -> None:
    """Say `ready` on stdout, then wait until stdin closes or SIGTERM."""
    import signal

    stop = asyncio.Event()
    asyncio.get_running_loop().add_signal_handler(signal.SIGTERM, stop.set)
    sys.stdout.write(ready + "\n")
    sys.stdout.flush()
    await stop.wait()


if __name__ == "__main__":
    role, port_arg = sys.argv[1], int(sys.argv[2])
    asyncio.run({"rpc": _serve_rpc, "pub": _serve_pub}[role](port_arg))
