"""The HTTP wire without stalls, pinned without timing anything: the server's accepted sockets
and robovoice's HTTP client sockets have ``TCP_NODELAY`` (no Nagle / delayed-ACK wait between
uvicorn's header and body writes), and a 2025-session tool call is answered with one plain
JSON response (so the client keeps its connection) unless something streams first."""

from __future__ import annotations

import json
import os
import socket
from collections.abc import Iterator
from pathlib import Path

import httpx2
import pytest
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from starlette.types import Message, Receive, Scope, Send

from robovoice.mcp_server import HttpEndpoint
from robovoice.mcp_server.bench_floor import ECHO_PATH, PAYLOAD, echo_app
from robovoice.mcp_server.http import asgi_server
from robovoice.mcp_server.sse_deferral import DeferSse
from robovoice.mcp_server.tcp import listen_tcp, nodelay_transport

from .mcp_testkit import Progress

# About the machine (a platform without /proc), not a missing install:
pytestmark = pytest.mark.skipif(not Path("/proc/self/fd").is_dir(), reason="finds sockets through /proc")


def _own_sockets() -> Iterator[socket.socket]:
    """This process's TCP sockets, as duplicates (closed by the caller's ``with``)."""
    for fd in os.listdir("/proc/self/fd"):
        try:
            sock = socket.socket(fileno=os.dup(int(fd)))
        except OSError:
            continue
        if sock.type != socket.SOCK_STREAM or sock.family not in (socket.AF_INET, socket.AF_INET6):
            sock.close()
            continue
        yield sock


def _peer_of(address: tuple[str, int]) -> socket.socket:
    """The socket of this process connected to `address` (the server's side of a connection)."""
    for sock in _own_sockets():
        try:
            if sock.getpeername()[:2] == address:
                return sock
        except OSError:
            pass
        sock.close()
    raise AssertionError(f"no socket of this process is connected to {address}")


def _nodelay(sock: socket.socket) -> int:
    return sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY)


def test_listener_hands_out_nodelay_sockets() -> None:
    with listen_tcp("127.0.0.1", 0) as listener, socket.create_connection(listener.getsockname()) as client:
        accepted, _ = listener.accept()
        with accepted:
            # asyncio sets TCP_NODELAY only on sockets whose proto is TCP; socket.create_server's are 0
            assert accepted.proto == socket.IPPROTO_TCP
            assert _nodelay(accepted) == 1
            assert client.proto in (0, socket.IPPROTO_TCP)


async def test_served_connections_have_nodelay(http: HttpEndpoint) -> None:
    """The MCP server's side of a live connection, found in this process."""
    async with httpx2.AsyncClient() as client:
        response = await client.post(http.url, json={"jsonrpc": "2.0", "id": 1, "method": "ping"},
                                     headers={"Accept": "application/json, text/event-stream"})
        assert response.status_code in (200, 400)  # what matters is the connection it came over
        stream = response.extensions["network_stream"]
        local = stream.get_extra_info("client_addr")
        with _peer_of(local[:2]) as served:
            assert _nodelay(served) == 1


async def test_robovoice_http_client_sets_nodelay() -> None:
    async with asgi_server(echo_app(), host="127.0.0.1", port=0) as endpoint, \
            httpx2.AsyncClient(transport=nodelay_transport()) as client:
        response = await client.post(f"http://127.0.0.1:{endpoint.port}{ECHO_PATH}", content=PAYLOAD)
        assert response.content == PAYLOAD
        sock = response.extensions["network_stream"].get_extra_info("socket")
        assert _nodelay(sock) == 1


async def test_a_2025_session_call_comes_back_as_json_on_one_connection(http: HttpEndpoint) -> None:
    seen: list[tuple[str, str, object]] = []

    async def record(response: httpx2.Response) -> None:
        local = response.extensions["network_stream"].get_extra_info("client_addr")
        seen.append((response.request.method, response.headers.get("content-type", ""), local))

    async with httpx2.AsyncClient(event_hooks={"response": [record]}) as http_client, \
            Client(streamable_http_client(http.url, http_client=http_client), mode="legacy") as client:
        await client.call_tool("get_navigation_targets", {})
        seen.clear()
        for _ in range(3):
            result = await client.call_tool("get_navigation_targets", {})
            assert not result.is_error
    posts = [(kind, local) for method, kind, local in seen if method == "POST"]
    assert [kind for kind, _ in posts] == ["application/json"] * 3
    assert len({local for _, local in posts}) == 1  # read to the end: the connection is kept


async def test_progress_still_streams_in_a_2025_session(http: HttpEndpoint) -> None:
    seen: list[str] = []

    async def record(response: httpx2.Response) -> None:
        if response.request.method == "POST":
            seen.append(response.headers.get("content-type", ""))

    progress = Progress()
    async with httpx2.AsyncClient(event_hooks={"response": [record]}) as http_client, \
            Client(streamable_http_client(http.url, http_client=http_client), mode="legacy") as client:
        seen.clear()
        result = await client.call_tool("navigate_to", {"target": "hallway"}, progress_callback=progress)
        assert not result.is_error
    assert progress.items and any(kind.startswith("text/event-stream") for kind in seen)  # navigate_to streamed


# --- DeferSse on its own, with scripted ASGI apps -------------------------------------------------

SSE_START: Message = {"type": "http.response.start", "status": 200,
                      "headers": [(b"content-type", b"text/event-stream; charset=utf-8"), (b"mcp-session-id", b"s1")]}
RESPONSE = {"jsonrpc": "2.0", "id": 7, "result": {"content": []}}
NOTIFICATION = {"jsonrpc": "2.0", "method": "notifications/progress", "params": {"progress": 1}}


def _event(body: object, *, event_id: str | None = None) -> bytes:
    head = f"id: {event_id}\r\n" if event_id else ""
    return f"{head}event: message\r\ndata: {json.dumps(body)}\r\n\r\n".encode()


def _chunk(data: bytes, more: bool = True) -> Message:
    return {"type": "http.response.body", "body": data, "more_body": more}


async def _through_defer(messages: list[Message], method: str = "POST") -> list[Message]:
    async def app(scope: Scope, receive: Receive, send: Send) -> None:
        for message in messages:
            await send(message)

    async def receive() -> Message:
        return {"type": "http.disconnect"}

    sent: list[Message] = []

    async def send(message: Message) -> None:
        sent.append(message)

    await DeferSse(app)({"type": "http", "method": method, "path": "/mcp"}, receive, send)
    return sent


async def test_a_lone_response_becomes_json() -> None:
    sent = await _through_defer([SSE_START, _chunk(_event(RESPONSE)), _chunk(b"", more=False)])
    assert len(sent) == 2
    headers = dict(sent[0]["headers"])
    assert headers[b"content-type"] == b"application/json" and headers[b"mcp-session-id"] == b"s1"
    assert json.loads(sent[1]["body"]) == RESPONSE and not sent[1]["more_body"]
    assert int(headers[b"content-length"]) == len(sent[1]["body"])


@pytest.mark.parametrize("first", [
    _event(NOTIFICATION),  # progress before the result: keep streaming
    _event(RESPONSE, event_id="e1"),  # resumable stream (an event store): keep its ids
    b": ping\r\n\r\n",  # keep-alive
    _event(RESPONSE) + _event(NOTIFICATION),  # more than one event
])
async def test_anything_else_stays_sse(first: bytes) -> None:
    messages = [SSE_START, _chunk(first), _chunk(_event(RESPONSE)), _chunk(b"", more=False)]
    assert await _through_defer(messages) == messages


async def test_other_responses_pass_untouched() -> None:
    plain = [{"type": "http.response.start", "status": 202, "headers": []}, _chunk(b"", more=False)]
    assert await _through_defer(plain) == plain
    stream = [SSE_START, _chunk(_event(RESPONSE)), _chunk(b"", more=False)]
    assert await _through_defer(stream, method="GET") == stream
    assert await _through_defer([SSE_START]) == [SSE_START, _chunk(b"", more=False)]
