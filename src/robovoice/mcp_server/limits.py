"""Bounds on request bodies at the network entry points (the MCP HTTP server, the console's API).

`BodyLimits` is ASGI middleware for HTTP requests that carry a body (POST, PUT, PATCH):

- a body over `max_bytes` (by ``Content-Length``, or counted as it arrives when chunked) is
  refused with **413** before it is all read — nothing past the limit is buffered;
- a JSON body nested deeper than `max_depth` (arrays and objects, outside strings) is refused
  with **400** — it would otherwise reach ``json.loads`` (a ``RecursionError``) and the
  validators;
- otherwise the buffered body is handed on unchanged.

The refusal is a JSON-RPC error (``{"jsonrpc": "2.0", "id": null, "error": {"code": -32600,
"message": …}}``) for the MCP server, or ``{"error": "too_large" | "too_deep", "message": …}``
with ``jsonrpc=False`` (the console's API shape).
"""

from __future__ import annotations

import json
import logging
from typing import Any

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from robovoice.json_limits import json_depth_exceeds

log = logging.getLogger(__name__)

MAX_BODY_BYTES = 1024 * 1024
MAX_JSON_DEPTH = 64
INVALID_REQUEST = -32600

_BODY_METHODS = frozenset({"POST", "PUT", "PATCH"})


class BodyLimits:
    """ASGI middleware: 413 for a body over `max_bytes`, 400 for JSON deeper than `max_depth`."""

    def __init__(self, app: ASGIApp, *, max_bytes: int = MAX_BODY_BYTES, max_depth: int = MAX_JSON_DEPTH,
                 jsonrpc: bool = True) -> None:
        self.app = app
        self.max_bytes = max_bytes
        self.max_depth = max_depth
        self.jsonrpc = jsonrpc

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope.get("method") not in _BODY_METHODS:
            await self.app(scope, receive, send)
            return
        declared = _content_length(scope)
        if declared is not None and declared > self.max_bytes:
            await self._refuse(send, 413, "too_large",
                               f"the request body is {declared} bytes; the limit is {self.max_bytes}")
            return
        chunks: list[bytes] = []
        size = 0
        while True:
            message = await receive()
            if message["type"] == "http.disconnect":
                return
            chunk = message.get("body", b"")
            size += len(chunk)
            if size > self.max_bytes:
                await self._refuse(send, 413, "too_large", f"the request body is over the limit of {self.max_bytes} "
                                                           "bytes")
                return
            chunks.append(chunk)
            if not message.get("more_body", False):
                break
        body = b"".join(chunks)
        if json_depth_exceeds(body, self.max_depth):
            await self._refuse(send, 400, "too_deep", f"the JSON body nests deeper than {self.max_depth} levels")
            return
        await self.app(scope, replaying({"type": "http.request", "body": body, "more_body": False}, receive), send)

    async def _refuse(self, send: Send, status: int, code: str, message: str) -> None:
        log.warning("refused a request: %s", message)
        payload: dict[str, Any]
        if self.jsonrpc:
            payload = {"jsonrpc": "2.0", "id": None, "error": {"code": INVALID_REQUEST, "message": message}}
        else:
            payload = {"error": code, "message": message}
        data = json.dumps(payload).encode("utf-8")
        await send({"type": "http.response.start", "status": status,
                    "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(data)).encode()),
                                (b"connection", b"close")]})
        await send({"type": "http.response.body", "body": data})


def _content_length(scope: Scope) -> int | None:
    for name, value in scope.get("headers", []):
        if name == b"content-length":
            try:
                return int(value)
            except ValueError:
                return None
    return None


def replaying(first: Message, rest: Receive) -> Receive:
    """A `receive` that gives `first` (a message already read) once, then defers to `rest` (the
    real one: later body parts, disconnects)."""
    given = False

    async def replay() -> Message:
        nonlocal given
        if not given:
            given = True
            return first
        return await rest()

    return replay
