"""Turning outcomes into MCP `CallToolResult`s.

- a result value: one text block with its JSON, and ``structuredContent`` (the value if it
  is an object, else ``{"result": value}``, since MCP 2025 clients accept only objects there);
- a `RobotFailure`: ``isError: true``, text JSON ``{error, message, hint, details}``, and the
  same object as ``structuredContent``;
- an image (``{"mime_type": "image/...", "data": <base64>}``, DESIGN's wire form for binary
  values): an MCP image block plus a short text block describing it.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import mcp_types as types

from robovoice.errors import RobotFailure


def to_json(value: Any) -> str:
    return json.dumps(value, ensure_ascii=False, separators=(", ", ": "), default=str)


def structured(value: Any) -> dict[str, Any]:
    return dict(value) if isinstance(value, Mapping) else {"result": value}


def value_result(value: Any) -> types.CallToolResult:
    return types.CallToolResult(
        content=[types.TextContent(text=to_json(value))], structured_content=structured(value)
    )


def failure_result(failure: RobotFailure) -> types.CallToolResult:
    body = failure.to_dict()
    return types.CallToolResult(
        content=[types.TextContent(text=to_json(body))], structured_content=body, is_error=True
    )


def image_result(mime_type: str, data: str, about: Mapping[str, Any]) -> types.CallToolResult:
    """An image block plus a text block with `about` (stamp, age, staleness, size) as JSON.

    No ``structuredContent``: it would repeat the whole image as base64 next to the image block.
    """
    return types.CallToolResult(
        content=[types.ImageContent(data=data, mime_type=mime_type), types.TextContent(text=to_json(dict(about)))],
    )
