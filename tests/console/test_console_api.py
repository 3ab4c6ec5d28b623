"""The console's API and WebSocket through real clients (httpx, websockets) against the real
server on a free port, the embedded sim robot and a scripted model (the fake OpenAI server)."""

from __future__ import annotations

import asyncio
import json
from typing import Any

import httpx
import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import InvalidStatus
from websockets.typing import Origin

from robovoice.console.serve import check_console_bind
from robovoice.errors import ConfigError
from robovoice.llm.fake_server import ScriptedCall, ScriptedReply, ToolCallReply

from .console_testkit import BOUND_S, next_message, running_console

GO_TO_KITCHEN: list[ScriptedReply] = [ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),))]


def _kinds(events: list[dict[str, Any]]) -> list[str]:
    return [e["kind"] for e in events]


async def test_say_returns_the_turn_and_the_websocket_streams_it_in_order() -> None:
    async with running_console(GO_TO_KITCHEN) as run, connect(f"{run.ws_base}/ws/events") as ws:
        hello = await next_message(ws, lambda m: m["type"] == "hello")
        assert hello["turns"] == [] and hello["voice"] == {"state": "off"}
        first = await next_message(ws, lambda m: m["type"] == "state" and "pose" in m["state"])
        assert first["state"]["pose"]["nearest_place"] == "charging dock"
        async with httpx.AsyncClient(base_url=run.base, timeout=BOUND_S) as http:
            response = await http.post("/api/say", json={"text": "please go to the kitchen"})
            assert response.status_code == 200, response.text
            turn = response.json()
            assert turn["calls"] == [{"name": "navigate_to", "arguments": {"target": "kitchen"}}]
            assert turn["reply"] == "I am in the kitchen now."  # the drive's success phrase
            kinds = _kinds(turn["events"])
            assert kinds[0] == "TurnStarted" and kinds[-1] == "TurnFinished"
            assert kinds.index("ToolCalled") < kinds.index("ToolReturned") < kinds.index("SentenceReady")
            assert "ToolProgressed" in kinds
            assert {"first_token", "finished"} <= set(turn["latency_ms"])
            returned = turn["events"][kinds.index("ToolReturned")]
            assert returned["is_error"] is False and returned["result"]["arrived"] == "kitchen"

            live: list[dict[str, Any]] = []

            def collect(message: dict[str, Any]) -> bool:
                live.append(message)
                return bool(message["type"] == "turn_end")

            end = await next_message(ws, collect)
            events = [m["event"] for m in live if m["type"] == "event" and m["turn"] == turn["turn"]]
            assert events == turn["events"]  # the same events, in the same order, live
            assert end["turn"] == turn["turn"] and end["latency_ms"] == turn["latency_ms"]

            state = await next_message(ws, lambda m: m["type"] == "state"
                                       and m["state"]["pose"]["nearest_place"] == "kitchen")
            assert state["state"]["path"], "the path driven is kept"
            snapshot = (await http.get("/api/state")).json()
            assert snapshot["turns"][-1]["id"] == turn["turn"] and not snapshot["turns"][-1]["open"]

            audit = (await http.get("/api/audit", params={"tool": "navigate_to"})).json()["records"]
            assert [(r["tool"], r["source"], r["outcome"]) for r in audit] == [("navigate_to", "typed", "ok")]


async def test_tools_by_hand_and_the_audit_log_newest_first_filtered() -> None:
    async with running_console() as run, httpx.AsyncClient(base_url=run.base, timeout=BOUND_S) as http:
        tools = {t["name"]: t for t in (await http.get("/api/tools")).json()["tools"]}
        assert tools["navigate_to"]["input_schema"]["required"] == ["target"] and tools["navigate_to"]["for_model"]
        ok = (await http.post("/api/call", json={"name": "get_navigation_targets"})).json()
        assert not ok["is_error"] and "kitchen" in json.dumps(ok["structured"])
        bad = (await http.post("/api/call", json={"name": "navigate_to", "arguments": {"target": "garage"}})).json()
        assert bad["is_error"] and bad["error"] == "unknown_target"
        image = (await http.post("/api/call", json={"name": "get_camera_image"})).json()
        assert any(block["type"] == "image" for block in image["content"])
        records = (await http.get("/api/audit")).json()["records"]
        assert [r["tool"] for r in records] == ["get_camera_image", "navigate_to", "get_navigation_targets"]
        errors = (await http.get("/api/audit", params={"errors": "true"})).json()["records"]
        assert [(r["tool"], r["error"]) for r in errors] == [("navigate_to", "unknown_target")]


async def test_bad_requests_get_400_with_a_message() -> None:
    async with running_console() as run, httpx.AsyncClient(base_url=run.base, timeout=BOUND_S) as http:
        for path, body in (("/api/say", b"{not json"), ("/api/say", b"[1]"), ("/api/say", b'{"text": ""}'),
                           ("/api/call", b'{"name": "x", "arguments": []}')):
            response = await http.post(path, content=body, headers={"Content-Type": "application/json"})
            assert response.status_code == 400, (path, body)
            assert response.json()["error"] == "bad_request" and response.json()["message"]
        assert (await http.get("/api/audit", params={"errors": "maybe"})).status_code == 400


async def test_foreign_origin_is_refused_on_the_page_the_api_and_the_websocket() -> None:
    async with running_console() as run, httpx.AsyncClient(base_url=run.base, timeout=BOUND_S) as http:
        evil = {"Origin": "http://evil.example"}
        assert (await http.get("/", headers=evil)).status_code == 403
        assert (await http.get("/api/state", headers=evil)).status_code == 403
        assert (await http.post("/api/say", json={"text": "go"}, headers=evil)).status_code == 403
        assert (await http.get("/api/state", headers={"Host": "evil.example"})).status_code == 421
        own = {"Origin": run.base}
        assert (await http.get("/", headers=own)).status_code == 200
        for path in ("/ws/events", "/ws/audio"):
            with pytest.raises(InvalidStatus) as refused:
                async with connect(f"{run.ws_base}{path}", origin=Origin("http://evil.example")):
                    pass
            assert refused.value.response.status_code == 403
        async with connect(f"{run.ws_base}/ws/events", origin=Origin(run.base)) as ws:
            assert (await next_message(ws, lambda m: m["type"] == "hello"))["robot_name"]


async def test_a_token_is_needed_off_loopback_and_then_on_every_path() -> None:
    with pytest.raises(ConfigError, match="token"):
        check_console_bind("0.0.0.0", None)
    check_console_bind("0.0.0.0", "x" * 32)
    token = "console-secret-0123456789"
    async with running_console(token=token) as run, httpx.AsyncClient(base_url=run.base, timeout=BOUND_S) as http:
        for path in ("/", "/api/state", "/api/tools", "/static/app.js"):
            assert (await http.get(path)).status_code == 401, path
        assert (await http.post("/api/say", json={"text": "hi"})).status_code == 401
        with pytest.raises(InvalidStatus) as refused:
            async with connect(f"{run.ws_base}/ws/events"):
                pass
        assert refused.value.response.status_code == 401
        bearer = {"Authorization": f"Bearer {token}"}
        assert (await http.get("/api/state", headers=bearer)).status_code == 200
        wrong = {"Authorization": "Bearer wrong-token-0123456"}
        assert (await http.get("/api/state", headers=wrong)).status_code == 401
        async with connect(f"{run.ws_base}/ws/events", additional_headers=bearer) as ws:
            assert (await next_message(ws, lambda m: m["type"] == "hello"))["turns"] == []
        # a browser signs in once; the cookie then carries the token (the page, the API, the WebSocket)
        assert (await http.post("/login", data={"token": "wrong"})).status_code == 401
        signed = await http.post("/login", data={"token": token})
        assert signed.status_code == 303 and "samesite=strict" in signed.headers["set-cookie"].lower()
        assert (await http.get("/api/state")).status_code == 200  # the client keeps the cookie
        cookie = f"robovoice_console_token={token}"
        async with connect(f"{run.ws_base}/ws/events", additional_headers={"Cookie": cookie}) as ws:
            await asyncio.wait_for(ws.recv(), BOUND_S)
