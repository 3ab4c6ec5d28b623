"""Fuzzing the console's API (the other network entry point) through the real console server:
random, malformed, oversized and deeply nested bodies on its POST routes, random query strings
on its GET routes. Never a 5xx, never a hang; 413/400 from the body bounds in the console's own
error shape; the console keeps answering."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import httpx
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from robovoice.json_limits import json_depth_exceeds
from robovoice.llm.fake_server import TextReply
from robovoice.mcp_server.limits import MAX_BODY_BYTES, MAX_JSON_DEPTH
from tests.console.console_testkit import Running, running_console

from .fuzzkit import JSON_VALUES, LoopThread, bounded, serving


@pytest.fixture(scope="module")
def console() -> Iterator[tuple[LoopThread, Running]]:
    with serving(lambda: running_console(default=TextReply("Okay."))) as running:
        yield running


BODY_FIELDS = st.fixed_dictionaries(
    {}, optional={"name": st.sampled_from(["get_battery_state", "stop_robot", "navigate_to", "", "nope"])
                  | JSON_VALUES, "arguments": JSON_VALUES, "text": st.text(max_size=40) | JSON_VALUES})
BODIES = st.one_of(
    BODY_FIELDS.map(lambda b: json.dumps(b).encode()),
    JSON_VALUES.map(lambda v: json.dumps(v).encode()),
    st.binary(max_size=120),
    st.integers(MAX_JSON_DEPTH - 2, 3000).map(lambda n: b'{"arguments":' * n + b"1" + b"}" * n),
)
CONTENT_TYPES = st.sampled_from(["application/json", "text/plain", "application/x-www-form-urlencoded"])
ROUTES = st.sampled_from(["/api/call", "/api/call", "/api/call", "/api/say", "/login", "/api/state"])


def test_console_api_garbage_is_answered(console: tuple[LoopThread, Running]) -> None:
    _, running = console
    with httpx.Client(base_url=running.base, timeout=30.0) as http:

        @bounded(120, deadline_ms=30_000)
        @given(ROUTES, BODIES, CONTENT_TYPES)
        @example("/api/call", b'{"name": "navigate_to", "arguments": {"target": [[[[[[[[1]]]]]]]]}}',
                 "application/json")
        def fuzz(route: str, body: bytes, content_type: str) -> None:
            response = http.post(route, content=body, headers={"content-type": content_type})
            assert response.status_code < 500, (route, body[:200], response.text[:300])
            if json_depth_exceeds(body, MAX_JSON_DEPTH) and route != "/api/state":
                assert response.status_code == 400 and response.json()["error"] == "too_deep"

        fuzz()

        @bounded(60)
        @given(st.dictionaries(st.sampled_from(["errors", "tool", "limit", "since", "source", "x"]),
                               st.text(max_size=12), max_size=3))
        def fuzz_query(params: dict[str, Any]) -> None:
            assert http.get("/api/audit", params=params).status_code < 500

        fuzz_query()
        too_big = http.post("/api/call", content=b" " * (MAX_BODY_BYTES + 1),
                            headers={"content-type": "application/json"})
        assert too_big.status_code == 413 and too_big.json()["error"] == "too_large"
        assert http.post("/api/call", json={"name": "get_battery_state"}).status_code == 200
