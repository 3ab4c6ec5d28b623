"""`DeferSse`: answer a 2025-era streamable-HTTP POST with plain JSON when the answer is all there is.

The SDK's 2025-11-25 session transport answers every request POST with an SSE stream
(``text/event-stream``, chunked) that carries the request's notifications and ends with
its response. A client stops reading once it has the response, before the stream's last
chunk, so its HTTP library cannot reuse the connection: every tool call then pays a new
TCP connection, and the SSE machinery, for a response that is usually the only thing
said. The spec lets the server pick JSON or SSE per POST (the client accepts both), and
the SDK's own 2026-07-28 path already defers SSE until there is something to stream.

`DeferSse` does the same for the 2025 path, as ASGI middleware: it holds back the start
of an SSE response to a POST until the first chunk. If that chunk is one plain
``message`` event holding a JSON-RPC response (a ``result`` or an ``error`` with an
``id``, no event id, so nothing to resume), the client gets it as
``application/json`` with a ``Content-Length`` (one response the client reads to the end:
the connection stays open for the next call), and the rest of the stream is dropped.
Anything else first (a progress notification, a server request, a priming event with an
event id, a keep-alive ping) commits to SSE unchanged: streaming works as before.
"""

from __future__ import annotations

import json

from starlette.types import ASGIApp, Message, Receive, Scope, Send

SSE_TYPE = b"text/event-stream"
JSON_TYPE = b"application/json"


class DeferSse:
    """ASGI middleware; see the module docstring."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope.get("method") != "POST":
            await self.app(scope, receive, send)
            return
        exchange = _Exchange(send)
        await self.app(scope, receive, exchange.send)
        await exchange.finish()


class _Exchange:
    """One POST's response on its way out: passed through, held (SSE start), or answered as JSON."""

    def __init__(self, send: Send) -> None:
        self._send = send
        self._held: Message | None = None
        self._done = False  # answered as JSON: later messages are dropped

    async def send(self, message: Message) -> None:
        if self._done:
            return
        if message["type"] == "http.response.start" and _content_type(message).startswith(SSE_TYPE):
            self._held = message
            return
        start = self._held
        if start is None:
            await self._send(message)
            return
        if message["type"] == "http.response.body" and message.get("more_body", False):
            response = _lone_response(message.get("body", b""))
            if response is not None:
                self._held, self._done = None, True
                await self._send(_json_start(start, len(response)))
                await self._send({"type": "http.response.body", "body": response, "more_body": False})
                return
        self._held = None
        await self._send(start)
        await self._send(message)

    async def finish(self) -> None:
        """The app returned with an SSE start still held (no body sent): send it, and an empty end."""
        start, self._held = self._held, None
        if start is not None and not self._done:
            await self._send(start)
            await self._send({"type": "http.response.body", "body": b"", "more_body": False})


def _content_type(start: Message) -> bytes:
    for name, value in start.get("headers", ()):
        if name.lower() == b"content-type":
            return bytes(value).lower()
    return b""


def _json_start(start: Message, length: int) -> Message:
    headers = [(name, value) for name, value in start.get("headers", ())
               if name.lower() not in (b"content-type", b"content-length", b"transfer-encoding")]
    headers += [(b"content-type", JSON_TYPE), (b"content-length", str(length).encode("ascii"))]
    return {**start, "headers": headers}


def _lone_response(chunk: bytes) -> bytes | None:
    """The JSON text of `chunk` if it is exactly one complete ``message`` event, without an
    event id, whose data is a JSON-RPC response; else None."""
    try:
        text = chunk.decode("utf-8").replace("\r\n", "\n").replace("\r", "\n")
    except UnicodeDecodeError:
        return None
    blocks = [block for block in text.split("\n\n") if block.strip("\n")]
    if len(blocks) != 1 or not text.endswith("\n\n"):
        return None
    event, data = "message", []
    for line in blocks[0].strip("\n").split("\n"):
        name, _, value = line.partition(":")
        if name == "event":
            event = value.removeprefix(" ")
        elif name == "data":
            data.append(value.removeprefix(" "))
        else:  # an id, a retry, a comment (a ping): not a lone response
            return None
    if event != "message" or len(data) != 1:
        return None
    try:
        body = json.loads(data[0])
    except ValueError:
        return None
    if not isinstance(body, dict) or "id" not in body or "method" in body or not ("result" in body or "error" in body):
        return None
    return data[0].encode("utf-8")
