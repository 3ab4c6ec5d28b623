"""Where an MCP tool call over streamable HTTP spends its time, client side vs server side.

``python -m robovoice.mcp_server.bench_split [-n CALLS] [--rounds R]`` — the same echo tool
call as `robovoice bench mcp` against robovoice's server (a child process, as there), in five
series, each run in turn for `n` calls per round:

- ``sdk_2025`` / ``sdk_2026``: the MCP SDK's client ``call_tool`` (a 2025-11-25 session, and
  the 2026-07-28 protocol): what an outside client pays;
- ``raw_2025`` / ``raw_2026``: the same JSON-RPC ``tools/call`` as one httpx2 POST with the
  headers the SDK client sends: the SDK client's share is the difference;
- ``http_echo``: the minimal HTTP echo (`bench_floor`), the floor.

For each: wall-clock p50 and mean, **client CPU** per call (this process, `time.process_time`)
and **server CPU** per call (the serving child's user + system time from ``/proc/PID/stat``,
in clock ticks: at 100 Hz, 1200 calls resolve 0.008 ms). CPU time is much less disturbed than
wall time by other jobs on a loaded machine, which makes it the better split.

``--in-process``: the server side alone, no network and no client: the ASGI app of
`build_http_app` (audit on) called directly with the same requests, against the HTTP echo's
app and `RobotToolServer.call_tool` alone; CPU per call of this process.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import os
import statistics
import sys
import time
from collections.abc import AsyncIterator, Awaitable, Callable
from dataclasses import dataclass
from typing import Any, Final

import httpx2
from mcp import Client

from robovoice.mcp_server.bench_floor import PAYLOAD
from robovoice.mcp_server.bench_inprocess import inprocess_split
from robovoice.mcp_server.tcp import nodelay_transport

WARMUP: Final = 30
ARGUMENTS: Final = {"text": "hello robot"}
META_2026: Final = {"io.modelcontextprotocol/protocolVersion": "2026-07-28",
                    "io.modelcontextprotocol/clientInfo": {"name": "bench_split", "version": "0"},
                    "io.modelcontextprotocol/clientCapabilities": {}}
ACCEPT: Final = {"accept": "application/json, text/event-stream", "content-type": "application/json"}

Call = Callable[[], Awaitable[object]]


@dataclass(frozen=True, slots=True)
class _Child:
    pid: int
    url: str


def server_cpu_s(pid: int) -> float:
    """User + system CPU seconds of process `pid` so far."""
    with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@contextlib.asynccontextmanager
async def _child(*module_args: str) -> AsyncIterator[_Child]:
    """``python -m MODULE ARGS`` printing ``ready URL ...``; terminated at the end."""
    process = await asyncio.create_subprocess_exec(sys.executable, "-m", *module_args,
                                                   stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.DEVNULL)
    try:
        assert process.stdout is not None
        async with asyncio.timeout(60):
            line = (await process.stdout.readline()).decode().split()
        if len(line) < 2 or line[0] != "ready":
            raise RuntimeError(f"{module_args[0]} did not start: {line!r}")
        yield _Child(process.pid, line[1])
    finally:
        if process.returncode is None:
            process.terminate()
            await process.wait()


def _checked(response: httpx2.Response) -> None:
    if response.status_code != 200 or b"hello robot" not in response.content:
        raise RuntimeError(f"the tool call answered {response.status_code} {response.content[:200]!r}")


async def _raw_2025(http: httpx2.AsyncClient, url: str) -> Call:
    """A 2025-11-25 session opened by hand, and its tools/call as one POST."""
    opened = await http.post(url, headers=ACCEPT, json={"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {
        "protocolVersion": "2025-11-25", "capabilities": {}, "clientInfo": {"name": "bench_split", "version": "0"}}})
    headers = {**ACCEPT, "mcp-session-id": opened.headers["mcp-session-id"], "mcp-protocol-version": "2025-11-25"}
    await http.post(url, headers=headers, json={"jsonrpc": "2.0", "method": "notifications/initialized"})
    body = json.dumps({"jsonrpc": "2.0", "id": 2, "method": "tools/call",
                       "params": {"name": "echo", "arguments": ARGUMENTS}}).encode()

    async def call() -> None:
        _checked(await http.post(url, headers=headers, content=body))

    return call


def _raw_2026(http: httpx2.AsyncClient, url: str) -> Call:
    headers = {**ACCEPT, "mcp-protocol-version": "2026-07-28", "mcp-method": "tools/call", "mcp-name": "echo"}
    body = json.dumps({"jsonrpc": "2.0", "id": 2, "method": "tools/call",
                       "params": {"name": "echo", "arguments": ARGUMENTS, "_meta": META_2026}}).encode()

    async def call() -> None:
        _checked(await http.post(url, headers=headers, content=body))

    return call


def _echo(http: httpx2.AsyncClient, url: str) -> Call:
    async def call() -> None:
        response = await http.post(url, content=PAYLOAD, headers={"content-type": "application/json"})
        if response.content != PAYLOAD:
            raise RuntimeError(f"the HTTP echo answered {response.status_code} {response.content[:100]!r}")

    return call


def _sdk(client: Client) -> Call:
    async def call() -> None:
        result = await client.call_tool("echo", ARGUMENTS)
        if result.is_error:
            raise RuntimeError(f"the tool call failed: {result.content}")

    return call


async def _measure(series: dict[str, tuple[Call, int]], n: int, rounds: int) -> dict[str, dict[str, float]]:
    """Each series `n` calls in turn, `rounds` times; wall samples and both sides' CPU."""
    samples: dict[str, list[float]] = {name: [] for name in series}
    client_cpu = dict.fromkeys(series, 0.0)
    server_cpu = dict.fromkeys(series, 0.0)
    for call, _ in series.values():
        for _ in range(WARMUP):
            await call()
    for _ in range(rounds):
        for name, (call, pid) in series.items():
            server0, client0 = server_cpu_s(pid), time.process_time()
            for _ in range(n):
                start = time.perf_counter()
                await call()
                samples[name].append((time.perf_counter() - start) * 1000.0)
            client_cpu[name] += time.process_time() - client0
            server_cpu[name] += server_cpu_s(pid) - server0
    calls = n * rounds
    return {name: {"p50_ms": round(statistics.median(s), 3), "mean_ms": round(statistics.fmean(s), 3),
                   "client_cpu_ms": round(client_cpu[name] / calls * 1000.0, 3),
                   "server_cpu_ms": round(server_cpu[name] / calls * 1000.0, 3), "calls": calls}
            for name, s in samples.items()}


async def bench_split(n: int = 300, rounds: int = 4) -> dict[str, Any]:
    """The five series (module docstring); plain numbers, with the load average before and after."""
    if n < 1 or rounds < 1:
        raise ValueError("n and rounds must be at least 1")
    load_before = _loadavg()
    async with _child("robovoice.mcp_server.bench", "robot", "http") as robot, \
            _child("robovoice.mcp_server.bench_floor", "net") as floor, \
            httpx2.AsyncClient(transport=nodelay_transport()) as http, \
            Client(robot.url, mode="legacy", cache=None) as sdk_2025, \
            Client(robot.url, mode="auto", cache=None) as sdk_2026:
        series = {
            "sdk_2025": (_sdk(sdk_2025), robot.pid), "sdk_2026": (_sdk(sdk_2026), robot.pid),
            "raw_2025": (await _raw_2025(http, robot.url), robot.pid),
            "raw_2026": (_raw_2026(http, robot.url), robot.pid),
            "http_echo": (_echo(http, floor.url), floor.pid),
        }
        results = await _measure(series, n, rounds)
    return {"n": n, "rounds": rounds, "load_before": load_before, "load_after": _loadavg(), "series": results}


def _loadavg() -> str:
    with open("/proc/loadavg", encoding="ascii") as load:
        return " ".join(load.read().split()[:3])


def format_split(report: dict[str, Any]) -> str:
    lines = [f"MCP tool call over streamable HTTP, {report['n']} x {report['rounds']} calls per series "
             f"(load average {report['load_before']} -> {report['load_after']})",
             f"  {'series':<10} {'p50 ms':>8} {'mean ms':>8} {'client CPU ms':>14} {'server CPU ms':>14}"]
    for name, row in report["series"].items():
        lines.append(f"  {name:<10} {row['p50_ms']:8.3f} {row['mean_ms']:8.3f} {row['client_cpu_ms']:14.3f} "
                     f"{row['server_cpu_ms']:14.3f}")
    return "\n".join(lines)


def format_inprocess(report: dict[str, Any]) -> str:
    lines = [f"Server side in process (no network, no client), {report['n']} x {report['rounds']} calls per series "
             f"(load average {report['load_before']} -> {report['load_after']}); CPU ms per call"]
    lines += [f"  {name:<22} {cpu:8.3f}" for name, cpu in report["cpu_ms"].items()]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m robovoice.mcp_server.bench_split",
                                     description="Client vs server time of an MCP call over streamable HTTP.")
    parser.add_argument("-n", type=int, default=300, help="calls per series per round (default 300)")
    parser.add_argument("--rounds", type=int, default=4, help="rounds over all series (default 4)")
    parser.add_argument("--in-process", action="store_true", help="the server side alone, ASGI calls in process")
    args = parser.parse_args(argv)
    if args.in_process:
        load_before = _loadavg()
        cpu_ms = asyncio.run(inprocess_split(args.n, args.rounds))
        print(format_inprocess({"n": args.n, "rounds": args.rounds, "cpu_ms": cpu_ms, "load_before": load_before,
                                "load_after": _loadavg()}))
    else:
        print(format_split(asyncio.run(bench_split(args.n, args.rounds))))


if __name__ == "__main__":
    main()
