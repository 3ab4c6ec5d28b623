"""Fuzzing tool arguments against their schemas, through the real MCP server in process (the
sim robot, the SDK client over in-memory JSON-RPC): every call answers with a result or a
structured tool error (``invalid_arguments`` for arguments its schema refuses) — never a
protocol error, never a hang."""

from __future__ import annotations

import json
import re
from collections.abc import AsyncIterator, Iterator
from contextlib import asynccontextmanager
from typing import Any

import mcp_types as types
import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from jsonschema import Draft202012Validator
from mcp import Client

from robovoice.address import SimAddress
from robovoice.mcp_server import open_robot_side
from robovoice.mcp_server.embedded import open_embedded_client

from .fuzzkit import JSON_VALUES, LoopThread, bounded, serving

SIM_SPEED = 200.0  # drives that do start finish in a fraction of a second
CODE = re.compile(r"^[a-z][a-z0-9_]*$")


@asynccontextmanager
async def _robot_client() -> AsyncIterator[tuple[Client, dict[str, dict[str, Any]]]]:
    async with (open_robot_side(SimAddress(speed=SIM_SPEED), manifests=None, audit_log=None) as side,
                open_embedded_client(side, snapshot_warmup_s=0.5) as client):
        listing = await client.list_tools()
        yield client, {t.name: dict(t.input_schema) for t in listing.tools}


@pytest.fixture(scope="module")
def robot() -> Iterator[tuple[LoopThread, tuple[Client, dict[str, dict[str, Any]]]]]:
    with serving(_robot_client) as running:
        yield running


def _value_for(schema: Any) -> st.SearchStrategy[Any]:
    """Mostly-right values for a property schema, with wrong ones mixed in."""
    if not isinstance(schema, dict):
        return JSON_VALUES
    kind = schema.get("type")
    right: st.SearchStrategy[Any]
    if "enum" in schema:
        right = st.sampled_from(schema["enum"])
    elif kind == "string":
        right = st.text(max_size=20) | st.sampled_from(["kitchen", "bedroom", "charging dock", "Alice", ""])
    elif kind in ("number", "integer"):
        right = st.integers(-5, 200) | st.floats(allow_nan=False, allow_infinity=False)
    elif kind == "boolean":
        right = st.booleans()
    else:
        right = JSON_VALUES
    return right | JSON_VALUES


@st.composite
def calls(draw: st.DrawFn, schemas: dict[str, dict[str, Any]]) -> tuple[str, dict[str, Any]]:
    name = draw(st.sampled_from(sorted(schemas)) | st.sampled_from(["", "navigate", "set_max_speed", "x" * 300]))
    properties = schemas.get(name, {}).get("properties", {})
    arguments: dict[str, Any] = {}
    for key, schema in properties.items():
        if draw(st.integers(0, 4)) > 0:
            arguments[key] = draw(_value_for(schema))
    arguments.update(draw(st.dictionaries(st.text(max_size=10), JSON_VALUES, max_size=2)))
    return name, arguments


def _check(result: types.CallToolResult, schema: dict[str, Any] | None, arguments: dict[str, Any]) -> None:
    assert isinstance(result, types.CallToolResult)
    valid = schema is not None and Draft202012Validator(schema).is_valid(arguments)
    if result.is_error:
        text = next(b for b in result.content if isinstance(b, types.TextContent)).text
        body = json.loads(text)
        assert CODE.match(body["error"]) and body["error"] != "internal_error", body
        assert isinstance(body["message"], str) and body["message"]
        if schema is None:
            assert body["error"] == "unknown_tool"
        elif not valid:
            assert body["error"] == "invalid_arguments", body
    else:
        assert valid, f"arguments the schema refuses were accepted: {arguments}"


def test_tool_arguments_give_a_result_or_a_structured_error(
        robot: tuple[LoopThread, tuple[Client, dict[str, dict[str, Any]]]]) -> None:
    loop, (client, schemas) = robot
    assert "navigate_to" in schemas

    @bounded(150, deadline_ms=10_000)
    @given(calls(schemas))
    @example(("navigate_to", {"target": {"$ref": "#"}}))
    @example(("navigate_to", {"target": "kitchen", "speed": 1e308}))
    @example(("set_projector_power", {"on": "yes"}))
    @example(("start_video_call", {"contact": "\x00" * 1000}))
    def fuzz(call: tuple[str, dict[str, Any]]) -> None:
        name, arguments = call
        _check(loop.run(client.call_tool(name, arguments)), schemas.get(name), arguments)

    fuzz()
    # and the server still answers properly afterwards
    assert not loop.run(client.call_tool("stop_robot", {})).is_error
