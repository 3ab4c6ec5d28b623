"""The server side of an MCP call over streamable HTTP alone: `build_http_app`'s ASGI app
called in process (no socket, no client) — ``python -m robovoice.mcp_server.bench_split
--in-process``.

Series: a 2025-11-25 session ``tools/call`` and a 2026-07-28 ``tools/call`` of the bench's
echo tool (audit on, as served), the HTTP echo floor's app with its payload, and
`RobotToolServer.call_tool` alone; CPU time of this process per call, the series interleaved
in rounds. Each response is checked as it comes back.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import tempfile
import time
from collections.abc import AsyncIterator, Awaitable, Callable
from pathlib import Path
from typing import Final

from starlette.types import ASGIApp, Message

from robovoice.mcp_server.bench import robot_server
from robovoice.mcp_server.bench_floor import ECHO_PATH, PAYLOAD, echo_app
from robovoice.mcp_server.http import MCP_PATH, build_http_app

WARMUP: Final = 50
ARGUMENTS: Final = {"text": "hello robot"}
_BASE: Final = [(b"host", b"127.0.0.1:8000"), (b"accept", b"application/json, text/event-stream"),
                (b"content-type", b"application/json")]
_META_2026: Final = {"io.modelcontextprotocol/protocolVersion": "2026-07-28",
                     "io.modelcontextprotocol/clientInfo": {"name": "bench_split", "version": "0"},
                     "io.modelcontextprotocol/clientCapabilities": {}}


async def post(app: ASGIApp, path: str, headers: list[tuple[bytes, bytes]], body: bytes) -> list[Message]:
    """One POST through `app`; the client never disconnects (receive waits after the body)."""
    scope = {"type": "http", "asgi": {"version": "3.0"}, "http_version": "1.1", "method": "POST", "scheme": "http",
             "path": path, "raw_path": path.encode(), "root_path": "", "query_string": b"",
             "server": ("127.0.0.1", 8000), "client": ("127.0.0.1", 50000),
             "headers": [*headers, (b"content-length", str(len(body)).encode())]}
    sent: list[Message] = []
    given = False
    never = asyncio.Event()

    async def receive() -> Message:
        nonlocal given
        if not given:
            given = True
            return {"type": "http.request", "body": body, "more_body": False}
        await never.wait()
        return {"type": "http.disconnect"}

    async def send(message: Message) -> None:
        sent.append(message)

    await app(scope, receive, send)
    return sent


def _answered(sent: list[Message], expect: bytes) -> None:
    if not any(expect in m.get("body", b"") for m in sent if m["type"] == "http.response.body"):
        raise RuntimeError(f"the call answered {sent!r:.300}")


@contextlib.asynccontextmanager
async def _lifespan(app: ASGIApp) -> AsyncIterator[None]:
    inbox: asyncio.Queue[Message] = asyncio.Queue()
    started, stopped = asyncio.Event(), asyncio.Event()

    async def send(message: Message) -> None:
        if message["type"] == "lifespan.startup.complete":
            started.set()
        elif message["type"] == "lifespan.shutdown.complete":
            stopped.set()

    async def run() -> None:
        await app({"type": "lifespan", "asgi": {"version": "3.0"}, "state": {}}, inbox.get, send)

    await inbox.put({"type": "lifespan.startup"})
    task = asyncio.create_task(run())
    async with asyncio.timeout(30):
        await started.wait()
    try:
        yield
    finally:
        await inbox.put({"type": "lifespan.shutdown"})
        async with asyncio.timeout(30):
            await task


async def _session_2025(app: ASGIApp) -> list[tuple[bytes, bytes]]:
    opened = await post(app, MCP_PATH, _BASE, json.dumps({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {
        "protocolVersion": "2025-11-25", "capabilities": {}, "clientInfo": {"name": "bench_split", "version": "0"}}},
    ).encode())
    session = dict(opened[0]["headers"])[b"mcp-session-id"]
    headers = [*_BASE, (b"mcp-session-id", session), (b"mcp-protocol-version", b"2025-11-25")]
    await post(app, MCP_PATH, headers, b'{"jsonrpc":"2.0","method":"notifications/initialized"}')
    return headers


async def inprocess_split(n: int = 2000, rounds: int = 2) -> dict[str, float]:
    """CPU ms per call of each series (module docstring)."""
    if n < 1 or rounds < 1:
        raise ValueError("n and rounds must be at least 1")
    with tempfile.TemporaryDirectory(prefix="robovoice-bench-") as tmp:
        async with robot_server(Path(tmp)) as (server, _):
            app, echo = build_http_app(server), echo_app()
            async with _lifespan(app):
                h25 = await _session_2025(app)
                b25 = json.dumps({"jsonrpc": "2.0", "id": 2, "method": "tools/call",
                                  "params": {"name": "echo", "arguments": ARGUMENTS}}).encode()
                h26 = [*_BASE, (b"mcp-protocol-version", b"2026-07-28"), (b"mcp-method", b"tools/call"),
                       (b"mcp-name", b"echo")]
                b26 = json.dumps({"jsonrpc": "2.0", "id": 2, "method": "tools/call",
                                  "params": {"name": "echo", "arguments": ARGUMENTS, "_meta": _META_2026}}).encode()

                async def call_2025() -> None:
                    _answered(await post(app, MCP_PATH, h25, b25), b"hello robot")

                async def call_2026() -> None:
                    _answered(await post(app, MCP_PATH, h26, b26), b"hello robot")

                async def http_echo() -> None:
                    _answered(await post(echo, ECHO_PATH, _BASE, PAYLOAD), PAYLOAD)

                async def call_tool() -> None:
                    if (await server.call_tool("echo", ARGUMENTS)).is_error:
                        raise RuntimeError("call_tool failed")

                series: dict[str, Callable[[], Awaitable[None]]] = {
                    "2025 session tools/call": call_2025, "2026-07-28 tools/call": call_2026,
                    "HTTP echo app": http_echo, "call_tool alone": call_tool}
                return await _cpu_per_call(series, n, rounds)


async def _cpu_per_call(series: dict[str, Callable[[], Awaitable[None]]], n: int, rounds: int) -> dict[str, float]:
    used = dict.fromkeys(series, 0.0)
    for call in series.values():
        for _ in range(WARMUP):
            await call()
    for _ in range(rounds):
        for name, call in series.items():
            start = time.process_time()
            for _ in range(n):
                await call()
            used[name] += time.process_time() - start
    return {name: round(seconds / (n * rounds) * 1000.0, 4) for name, seconds in used.items()}


