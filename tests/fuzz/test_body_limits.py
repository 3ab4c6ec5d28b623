"""The body bounds on the network entry points: 413 past the size (declared or streamed), 400
past the nesting depth, the body handed on unchanged otherwise; the console's shape."""

from __future__ import annotations

import time
from collections.abc import Iterator

from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import JSONResponse
from starlette.routing import Route
from starlette.testclient import TestClient

from robovoice.json_limits import json_depth_exceeds
from robovoice.mcp_server.limits import BodyLimits


async def echo(request: Request) -> JSONResponse:
    return JSONResponse({"size": len(await request.body())})


def _client(**options: object) -> TestClient:
    return TestClient(BodyLimits(Starlette(routes=[Route("/", echo, methods=["GET", "POST"])]), max_bytes=1000,
                                 max_depth=5, **options))  # type: ignore[arg-type]  # any of its keyword options


def test_depth_ignores_brackets_in_strings_and_counts_both_kinds() -> None:
    assert not json_depth_exceeds(b'{"a": "[[[[[[[[[[[[", "b": [1, [2]]}', 3)
    assert json_depth_exceeds(b'{"a": [{"b": [1]}]}', 3)
    assert not json_depth_exceeds(b'{"a": [{"b": [1]}]}', 4)
    assert not json_depth_exceeds(b'"\\"[[[[[[["', 1)  # an escaped quote does not end the string
    assert json_depth_exceeds(b"[" * 10, 5)  # unclosed: measured as far as it goes


def test_bodies_within_bounds_pass_unchanged() -> None:
    with _client() as client:
        assert client.post("/", content=b'{"a": [[[1]]]}').json() == {"size": 14}
        assert client.get("/").json() == {"size": 0}


def test_a_declared_or_streamed_oversized_body_is_413_with_a_json_rpc_error() -> None:
    def chunks() -> Iterator[bytes]:
        for _ in range(20):
            yield b"x" * 100

    with _client() as client:
        declared = client.post("/", content=b"x" * 1001)
        streamed = client.post("/", content=chunks())  # chunked: no Content-Length
    for response in (declared, streamed):
        assert response.status_code == 413
        assert response.json()["jsonrpc"] == "2.0" and response.json()["error"]["code"] == -32600
        assert "limit" in response.json()["error"]["message"]


def test_too_deep_is_400_and_the_console_gets_its_own_error_shape() -> None:
    with _client(jsonrpc=False) as client:
        deep = client.post("/", content=b"[[[[[[[]]]]]]]")
        big = client.post("/", content=b"x" * 2000)
    assert deep.status_code == 400 and deep.json()["error"] == "too_deep"
    assert big.status_code == 413 and big.json()["error"] == "too_large"


def test_the_depth_scan_is_linear_on_hostile_bodies() -> None:
    # an unterminated string full of escaped quotes used to be rescanned from every quote (hours)
    hostile = [b'"' + b'\\"' * 500_000 + b"[" * 70, b'"' + b"[" * 1_000_000, b'"\\' * 500_000 + b"{" * 70]
    started = time.perf_counter()
    assert [json_depth_exceeds(body, 64) for body in hostile] == [False, False, False]
    assert time.perf_counter() - started < 5.0  # ~0.2 s; the quadratic scan took hours on these
