"""`JsonFirst`: a 2026-07-28 request that cannot stream is served on the SDK's JSON path, and
keeps what the SSE path gave it (progress streams, a disconnect cancels, a long call pings),
pinned without timing anything."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import httpx2
import pytest
from mcp import Client
from mcp.server._streamable_http_modern import handle_modern_request
from starlette.types import Receive, Scope, Send

from robovoice.address import SimAddress
from robovoice.mcp_server import HttpEndpoint, RobotSide, http_server, open_robot_side
from robovoice.mcp_server.http import asgi_server, build_http_app
from robovoice.mcp_server.json_first import answers_with_json

from .mcp_testkit import BOUND_S, DRIVING, Progress, body, wait_for_message

META = {"io.modelcontextprotocol/protocolVersion": "2026-07-28",
        "io.modelcontextprotocol/clientInfo": {"name": "test", "version": "0"},
        "io.modelcontextprotocol/clientCapabilities": {}}
BOTH = "application/json, text/event-stream"


def _call(name: str, arguments: dict[str, Any], *, request_id: int = 7, **meta: Any) -> dict[str, Any]:
    return {"jsonrpc": "2.0", "id": request_id, "method": "tools/call",
            "params": {"name": name, "arguments": arguments, "_meta": {**META, **meta}}}


def _headers(name: str, accept: str = BOTH, version: str = "2026-07-28") -> dict[str, str]:
    return {"accept": accept, "content-type": "application/json", "mcp-protocol-version": version,
            "mcp-method": "tools/call", "mcp-name": name}


def _scope(headers: dict[str, str]) -> Scope:
    return {"type": "http", "method": "POST",
            "headers": [(k.encode("latin-1"), v.encode("latin-1")) for k, v in headers.items()]}


# --- which requests take the JSON path ----------------------------------------------------------

@pytest.mark.parametrize(("headers", "message", "json_mode"), [
    (_headers("noop"), _call("noop", {}), True),
    (_headers("noop"), {"jsonrpc": "2.0", "id": 1, "method": "tools/list"}, True),
    (_headers("noop", accept="*/*"), _call("noop", {}), True),
    # progress has to stream: the SDK's SSE path
    (_headers("noop"), _call("noop", {}, progressToken="p1"), False),
    # the SDK answers these as it always did (406 for JSON-only Accept, 202 for a notification)
    (_headers("noop", accept="application/json"), _call("noop", {}), False),
    (_headers("noop"), {"jsonrpc": "2.0", "method": "notifications/cancelled", "params": {}}, False),
    (_headers("noop"), {"jsonrpc": "2.0", "id": 1, "method": "subscriptions/listen"}, False),
    (_headers("noop"), {"jsonrpc": "2.0", "id": 1, "method": "tools/call", "params": ["x"]}, False),
    # the 2025 session path (and a request without a version header) is the SDK's, untouched
    (_headers("noop", version="2025-11-25"), _call("noop", {}), False),
    ({"accept": BOTH}, _call("noop", {}), False),
])
def test_which_requests_are_answered_with_json(headers: dict[str, str], message: object, json_mode: bool) -> None:
    assert answers_with_json(_scope(headers), json.dumps(message).encode()) is json_mode


def test_a_body_that_is_not_json_goes_to_the_sdk() -> None:
    assert answers_with_json(_scope(_headers("noop")), b"{not json") is False


# --- over a real server -----------------------------------------------------------------------

@pytest.fixture
def modern_entry(monkeypatch: pytest.MonkeyPatch) -> list[bool]:
    """The ``json_response`` each 2026-07-28 request reached the SDK's entry with."""
    seen: list[bool] = []

    async def spy(app: Any, security: Any, json_response: bool, state: Any, scope: Scope, receive: Receive,
                  send: Send) -> None:
        seen.append(json_response)
        await handle_modern_request(app, security, json_response, state, scope, receive, send)

    monkeypatch.setattr("mcp.server.streamable_http_manager.handle_modern_request", spy)  # where it is called
    return seen


async def test_a_call_without_progress_takes_the_json_path(http: HttpEndpoint, modern_entry: list[bool]) -> None:
    async with Client(http.url, mode="auto") as client:
        await client.call_tool("get_robot_pose", {})  # the client lists the tools after its first call
        modern_entry.clear()
        result = await client.call_tool("get_navigation_targets", {})
        assert not result.is_error and "kitchen" in json.dumps(body(result))
        assert modern_entry == [True]
        modern_entry.clear()
        progress = Progress()
        driven = await client.call_tool("navigate_to", {"target": "hallway"}, progress_callback=progress)
        assert not driven.is_error and progress.items  # progress streamed, on the SSE path
        assert modern_entry == [False]


async def test_errors_keep_the_sdks_status_and_shape(http: HttpEndpoint) -> None:
    async with httpx2.AsyncClient() as client:
        ok = await client.post(http.url, headers=_headers("get_robot_pose"), json=_call("get_robot_pose", {}))
        assert ok.status_code == 200 and ok.headers["content-type"] == "application/json"
        assert ok.json()["id"] == 7 and ok.json()["result"]["isError"] is False
        # the Mcp-Name header contradicts the body: the SDK's header check, as before
        mismatch = await client.post(http.url, headers=_headers("stop_robot"), json=_call("get_robot_pose", {}))
        assert mismatch.status_code == 400 and mismatch.json()["id"] == 7 and "error" in mismatch.json()
        # a client that does not accept SSE is refused as before (the server streams progress)
        json_only = await client.post(http.url, headers=_headers("get_robot_pose", accept="application/json"),
                                      json=_call("get_robot_pose", {}))
        assert json_only.status_code == 406
        unknown = await client.post(http.url, headers=_headers("fly"), json=_call("fly", {}))
        assert unknown.status_code == 200 and unknown.json()["result"]["isError"] is True


@pytest.fixture
async def driving(audit_path: Path) -> AsyncIterator[RobotSide]:
    async with open_robot_side(SimAddress(speed=DRIVING), manifests=None, audit_log=audit_path) as robot:
        yield robot


async def test_closing_the_connection_cancels_a_json_mode_call(driving: RobotSide, audit_path: Path,
                                                               modern_entry: list[bool]) -> None:
    sim = driving.sim
    assert sim is not None
    async with http_server(driving.server) as endpoint, Client(endpoint.url, mode="auto") as client:
        await client.call_tool("get_robot_pose", {})  # the client lists the tools after its first call
        modern_entry.clear()
        drive = asyncio.create_task(client.call_tool("navigate_to", {"target": "front door"}))
        async with asyncio.timeout(BOUND_S):
            while not sim.state.moving:
                await asyncio.sleep(0.01)
        assert modern_entry == [True]
        drive.cancel()
        with pytest.raises(asyncio.CancelledError):
            await drive
        stopped = await wait_for_message(driving.middleware, "pose", lambda v: v["moving"] is False)
        assert stopped["nearest_place"] != "front door" and sim.state.driving_target is None
        async with asyncio.timeout(BOUND_S):  # the handler was cancelled, and audited so
            while not audit_path.read_text().strip():
                await asyncio.sleep(0.01)
        record = json.loads(audit_path.read_text().splitlines()[-1])
        assert record["tool"] == "navigate_to" and record["error"]["error"] == "cancelled"


async def test_a_long_call_pings_then_answers_on_the_stream(driving: RobotSide) -> None:
    app = build_http_app(driving.server, keepalive_s=0.2)
    async with asgi_server(app, host="127.0.0.1", port=0) as endpoint, httpx2.AsyncClient() as client:
        async with client.stream("POST", endpoint.url, headers=_headers("navigate_to"),
                                 json=_call("navigate_to", {"target": "kitchen"}), timeout=BOUND_S) as response:
            assert response.status_code == 200
            assert response.headers["content-type"] == "text/event-stream"
            text = "".join([chunk async for chunk in response.aiter_text()])
        pings, _, last = text.rpartition("event: message\r\n")
        assert pings.startswith(": ping\r\n\r\n") and set(pings.split("\r\n\r\n")) == {": ping", ""}
        assert last.startswith("data: ") and last.endswith("\r\n\r\n")
        message = json.loads(last.removeprefix("data: "))
        assert message["id"] == 7 and message["result"]["isError"] is False
        # the SDK's own client reads such a stream as the call's result
        async with Client(endpoint.url, mode="auto") as sdk_client:
            result = await sdk_client.call_tool("navigate_to", {"target": "hallway"})
            assert not result.is_error and body(result)["arrived"] == "hallway"
