"""Fuzzing the MCP server's streamable-HTTP endpoint with JSON-RPC messages — malformed,
oversized, deeply nested, wrong types, unknown methods, odd headers — through a real uvicorn
on a free loopback port and httpx. Every request gets an answer (never a 5xx, never a hang:
each is bounded), the body-size and nesting bounds answer 413/400 with a JSON-RPC error, and
the server keeps serving a client that was connected all along, and new ones."""

from __future__ import annotations

import json
from collections.abc import AsyncIterator, Iterator
from contextlib import asynccontextmanager
from typing import Any

import httpx
import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from mcp import Client

from robovoice.address import SimAddress
from robovoice.json_limits import json_depth_exceeds
from robovoice.mcp_server import HttpEndpoint, http_server, open_robot_side
from robovoice.mcp_server.limits import MAX_BODY_BYTES, MAX_JSON_DEPTH

from .fuzzkit import JSON_VALUES, SCALARS, LoopThread, bounded, serving

Served = tuple[HttpEndpoint, Client]


@asynccontextmanager
async def _served() -> AsyncIterator[Served]:
    async with (open_robot_side(SimAddress(speed=200.0), manifests=None, audit_log=None) as side,
                http_server(side.server, port=0) as endpoint,
                Client(endpoint.url, mode="legacy") as bystander):
        await bystander.list_tools()
        yield endpoint, bystander


@pytest.fixture(scope="module")
def served() -> Iterator[tuple[LoopThread, Served]]:
    with serving(_served) as running:
        yield running


METHODS = st.sampled_from(["initialize", "ping", "tools/list", "tools/call", "notifications/initialized",
                           "notifications/cancelled", "resources/list", "prompts/get", "completion/complete",
                           "subscriptions/listen", "logging/setLevel", "", "rpc.discover", "tools/call/x"])
MESSAGES = st.fixed_dictionaries(
    {}, optional={"jsonrpc": st.sampled_from(["2.0", "1.0", 2]) | SCALARS, "id": SCALARS | JSON_VALUES,
                  "method": METHODS | SCALARS, "params": JSON_VALUES | st.fixed_dictionaries(
                      {}, optional={"name": st.sampled_from(["navigate_to", "stop_robot", "nope"]) | SCALARS,
                                    "arguments": JSON_VALUES, "protocolVersion": SCALARS,
                                    "capabilities": JSON_VALUES, "clientInfo": JSON_VALUES, "_meta": JSON_VALUES}),
                  "result": JSON_VALUES, "error": JSON_VALUES})


def _nested(depth: int, kind: str) -> bytes:
    return (b"[" * depth + b"]" * depth) if kind == "a" else (b'{"a":' * depth + b"1" + b"}" * depth)


BODIES = st.one_of(
    MESSAGES.map(lambda m: json.dumps(m).encode()),
    st.lists(MESSAGES, max_size=3).map(lambda m: json.dumps(m).encode()),
    st.binary(max_size=200),
    JSON_VALUES.map(lambda v: json.dumps(v).encode()),
    MESSAGES.map(lambda m: json.dumps(m).encode()[: len(json.dumps(m)) // 2]),
    st.tuples(st.integers(MAX_JSON_DEPTH - 2, 5000), st.sampled_from("ao")).map(lambda d: _nested(*d)),
)
HEADERS = st.fixed_dictionaries(
    {"accept": st.sampled_from(["application/json, text/event-stream", "application/json", "*/*", "text/html"]),
     "content-type": st.sampled_from(["application/json", "text/plain", "application/json; charset=latin-1", ""])},
    optional={"mcp-session-id": st.sampled_from(["", "nope", "0" * 64, "\u00e9"]) | st.text("0123456789abcdef"),
              "mcp-protocol-version": st.sampled_from(["2025-06-18", "2025-03-26", "2026-07-28", "1999-01-01", ""]),
              "last-event-id": st.text("0123456789-", max_size=10)},
)


def _check(response: httpx.Response, body: bytes) -> None:
    assert response.status_code < 500, (response.status_code, response.text[:300], body[:200])
    if response.status_code in (400, 413) and response.headers.get("content-type", "").startswith("application/json"):
        payload = response.json()
        assert "error" in payload or "jsonrpc" in payload


def test_json_rpc_garbage_over_http_is_answered_and_the_server_keeps_serving(
        served: tuple[LoopThread, Served]) -> None:
    loop, (endpoint, bystander) = served
    with httpx.Client(timeout=10.0) as http:

        @bounded(250, deadline_ms=10_000)
        @given(BODIES, HEADERS, st.sampled_from(["POST"] * 8 + ["DELETE", "PUT", "GET"]))
        @example(_nested(MAX_JSON_DEPTH + 1, "a"), {"accept": "application/json, text/event-stream",
                                                    "content-type": "application/json"}, "POST")
        @example(_nested(100_000, "o"), {"accept": "application/json, text/event-stream",
                                         "content-type": "application/json"}, "POST")
        @example(b'{"jsonrpc": "2.0", "id": 1, "method": "tools/call", "params": {"name": "navigate_to", '
                 b'"arguments": {"target": [[[[[[]]]]]]}}}', {"accept": "application/json, text/event-stream",
                                                            "content-type": "application/json",
                                                            "mcp-protocol-version": "2026-07-28"}, "POST")
        def fuzz(body: bytes, headers: dict[str, str], method: str) -> None:
            if method == "GET":  # a GET on a live session is an open event stream: only ask with a bad id
                headers = {**headers, "mcp-session-id": "not-a-session", "accept": "text/event-stream"}
            response = http.request(method, endpoint.url, content=body if method != "GET" else None,
                                    headers={k: v for k, v in headers.items() if v.isascii()})
            _check(response, body)
            if method in ("POST", "PUT") and json_depth_exceeds(body, MAX_JSON_DEPTH):
                assert response.status_code == 400
                assert response.json()["error"]["code"] == -32600

        fuzz()
        too_big = http.post(endpoint.url, content=b" " * (MAX_BODY_BYTES + 1),
                            headers={"content-type": "application/json", "accept": "application/json"})
        assert too_big.status_code == 413 and too_big.json()["error"]["code"] == -32600

    # the client connected all along still works, and a new one too
    assert not loop.run(bystander.call_tool("stop_robot", {})).is_error

    async def fresh() -> Any:
        async with Client(endpoint.url, mode="legacy") as client:
            return await client.call_tool("get_battery_state", {})

    assert not loop.run(fresh()).is_error
