"""The floors of `robovoice bench mcp`: what each transport costs with nothing on it.

- **HTTP echo**: a POST of a tool-call-sized JSON body to a one-route Starlette app under
  uvicorn, served exactly as the MCP server is (`asgi_server`: same listener, same
  uvicorn, same loop), answered with the body; the client is httpx2, the MCP SDK's HTTP
  client. No MCP server does less than this per call.
- **TCP**: the same bytes over a raw loopback TCP connection to an asyncio echo server
  (``TCP_NODELAY`` on both ends): the wire and the two event loops, nothing else.
- **Pipe**: one line to a child process that writes it back (stdin/stdout), as the stdio
  transport's floor.

The child processes are ``python -m robovoice.mcp_server.bench_floor {net|pipe}``; ``net``
prints ``ready <echo URL> <tcp port>``.
"""

from __future__ import annotations

import asyncio
import contextlib
import sys
from collections.abc import AsyncIterator, Awaitable, Callable

import httpx2
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import Response
from starlette.routing import Route

from robovoice.mcp_server.tcp import listen_tcp, nodelay_transport

ECHO_PATH = "/echo"
PAYLOAD = (b'{"jsonrpc":"2.0","id":1,"method":"tools/call",'
           b'"params":{"name":"echo","arguments":{"text":"hello robot"}}}')
"""About the size of the benchmark's MCP tool call."""

Call = Callable[[], Awaitable[object]]


# --- the servers (child processes) ----------------------------------------------------------


async def _echo(request: Request) -> Response:
    return Response(await request.body(), media_type="application/json")


def echo_app() -> Starlette:
    """The minimal HTTP app: POST `ECHO_PATH` answers with the request body."""
    return Starlette(routes=[Route(ECHO_PATH, _echo, methods=["POST"])])


async def _echo_bytes(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
    with contextlib.closing(writer):
        while data := await reader.read(65536):
            writer.write(data)
            await writer.drain()


async def _serve_net() -> None:
    from robovoice.mcp_server.http import asgi_server

    async with asgi_server(echo_app(), host="127.0.0.1", port=0) as endpoint:
        tcp = await asyncio.start_server(_echo_bytes, sock=listen_tcp("127.0.0.1", 0))
        async with tcp:
            port = tcp.sockets[0].getsockname()[1]
            print(f"ready http://127.0.0.1:{endpoint.port}{ECHO_PATH} {port}", flush=True)
            await asyncio.Event().wait()


def _serve_pipe() -> None:
    for line in sys.stdin.buffer:
        sys.stdout.buffer.write(line)
        sys.stdout.buffer.flush()


# --- the clients ------------------------------------------------------------------------------


@contextlib.asynccontextmanager
async def net_floors() -> AsyncIterator[dict[str, Call]]:
    """The HTTP echo and TCP round trips (a child process serves both), as timed calls."""
    process = await asyncio.create_subprocess_exec(sys.executable, "-m", "robovoice.mcp_server.bench_floor", "net",
                                                   stdout=asyncio.subprocess.PIPE,
                                                   stderr=asyncio.subprocess.DEVNULL)
    try:
        assert process.stdout is not None
        async with asyncio.timeout(60):
            line = (await process.stdout.readline()).decode().split()
        if len(line) != 3 or line[0] != "ready":
            raise RuntimeError(f"the floor server did not start: {line!r}")
        url, port = line[1], int(line[2])
        reader, writer = await asyncio.open_connection("127.0.0.1", port)
        async with httpx2.AsyncClient(transport=nodelay_transport()) as client:

            async def http_echo() -> object:
                response = await client.post(url, content=PAYLOAD, headers={"content-type": "application/json"})
                if response.content != PAYLOAD:
                    raise RuntimeError(f"the HTTP echo answered {response.status_code} {response.content[:100]!r}")
                return None

            async def tcp() -> object:
                writer.write(PAYLOAD + b"\n")
                if await reader.readline() != PAYLOAD + b"\n":
                    raise RuntimeError("the TCP echo answered something else")
                return None

            try:
                yield {"http_echo": http_echo, "tcp": tcp}
            finally:
                writer.close()
    finally:
        if process.returncode is None:
            process.terminate()
            await process.wait()


@contextlib.asynccontextmanager
async def pipe_floor() -> AsyncIterator[Call]:
    """The pipe round trip to a child process, as a timed call."""
    process = await asyncio.create_subprocess_exec(sys.executable, "-m", "robovoice.mcp_server.bench_floor", "pipe",
                                                   stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE)
    assert process.stdin is not None and process.stdout is not None
    stdin, stdout = process.stdin, process.stdout

    async def pipe() -> object:
        stdin.write(PAYLOAD + b"\n")
        if await stdout.readline() != PAYLOAD + b"\n":
            raise RuntimeError("the pipe echo answered something else")
        return None

    try:
        yield pipe
    finally:
        stdin.close()
        async with asyncio.timeout(10):
            await process.wait()


if __name__ == "__main__":
    with contextlib.suppress(KeyboardInterrupt):
        if sys.argv[1] == "pipe":
            _serve_pipe()
        else:
            asyncio.run(_serve_net())
