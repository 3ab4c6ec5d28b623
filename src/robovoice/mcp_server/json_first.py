"""`JsonFirst`: a 2026-07-28 request that cannot stream is answered on the SDK's JSON path.

For a 2026-07-28 POST the SDK's streamable-HTTP entry in SSE mode (robovoice's mode: progress
must stream) runs the handler as a sibling task beside a disconnect watcher, behind a
zero-buffer memory stream and a deferral window, and answers with plain JSON when the
handler said nothing before its response. That machinery costs about as much server CPU
per call as everything else in the request (docs/performance.md). The SDK's JSON-response
mode writes the one response from the request's own task instead, but it drops every
notification, so a whole server cannot run in it.

What a robovoice tool says while it runs is progress, and only to a request that carries a
``progressToken`` (`ToolCalls`; no tool logs to the client or asks it anything). A request
without one can only ever be answered by its response, so `JsonFirst` serves it in JSON mode:
`JsonFirstSessionManager` reads its ``json_response`` per request, from a context variable
that `JsonFirst` sets around that one request. Everything else — the 2025 session path, a
request with a ``progressToken``, ``subscriptions/listen``, a notification, a client that
does not accept both JSON and SSE (the SDK's 406 stays) — goes to the SDK as before.

What the SSE mode gave a JSON-mode call, `JsonFirst` keeps:

- **cancellation**: a client that closes the connection cancels the call (the handler's
  audit record says ``cancelled``, the node stops the action); the watch starts once a call
  has run `WATCH_AFTER_S` (20 ms), so a quick call costs a timer rather than a task;
- **keep-alive**: a call still running after `KEEPALIVE_S` (the SDK's SSE ping interval)
  commits to ``text/event-stream`` with a ``: ping`` comment every interval, and its
  response goes out as the stream's one ``message`` event, as the SDK's SSE mode does.
"""

from __future__ import annotations

import asyncio
import json
from contextvars import ContextVar
from typing import Final

import anyio
from mcp.server.streamable_http_manager import StreamableHTTPSessionManager
from mcp.shared.inbound import MCP_PROTOCOL_VERSION_HEADER
from mcp_types.version import HANDSHAKE_PROTOCOL_VERSIONS
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from robovoice.mcp_server.limits import replaying

KEEPALIVE_S: Final = 15.0
"""Seconds of silence before a JSON-mode call commits to SSE and pings (the SDK's interval)."""

WATCH_AFTER_S: Final = 0.02
"""A call still running after this long is watched for a disconnect (cancelled at most this late)."""

_JSON_MODE: ContextVar[bool] = ContextVar("robovoice_mcp_json_mode", default=False)
_VERSION_HEADER: Final = MCP_PROTOCOL_VERSION_HEADER.lower().encode("ascii")
_SSE_HEADERS: Final = [(b"content-type", b"text/event-stream"), (b"cache-control", b"no-cache, no-transform"),
                       (b"connection", b"keep-alive"), (b"x-accel-buffering", b"no")]
_PING: Final = b": ping\r\n\r\n"


class JsonFirstSessionManager(StreamableHTTPSessionManager):
    """The SDK's session manager, in JSON-response mode for exactly the requests `JsonFirst`
    marks (the manager reads ``json_response`` per request, in the request's task)."""

    @property  # the SDK stores a plain attribute; here it is read per request
    def json_response(self) -> bool:
        return _JSON_MODE.get()

    @json_response.setter
    def json_response(self, value: bool) -> None:
        if value:
            raise ValueError("JsonFirstSessionManager picks JSON per request; do not set json_response")


def answers_with_json(scope: Scope, body: bytes) -> bool:
    """Whether `JsonFirst` serves this POST in JSON mode: a 2026-07-28-era request (a protocol
    header the handshake does not own, as the SDK routes it) whose client accepts JSON and SSE,
    one JSON-RPC request other than ``subscriptions/listen``, without a ``progressToken``."""
    version: bytes | None = None
    accept: bytes | None = None
    for name, value in scope.get("headers", ()):  # the first of each, as the SDK reads them
        if name == _VERSION_HEADER and version is None:
            version = value
        elif name == b"accept" and accept is None:
            accept = value
    if version is None or version.decode("latin-1") in HANDSHAKE_PROTOCOL_VERSIONS or not _accepts_both(accept or b""):
        return False
    try:
        message = json.loads(body)
    except (ValueError, RecursionError):
        return False  # the SDK answers the parse error
    if not isinstance(message, dict) or "id" not in message or message.get("method") == "subscriptions/listen":
        return False
    params = message.get("params")
    if params is None:
        return True
    if not isinstance(params, dict):
        return False
    meta = params.get("_meta")
    return meta is None or (isinstance(meta, dict) and "progressToken" not in meta)


def _accepts_both(accept: bytes) -> bool:
    """``Accept`` names JSON and SSE (wildcards too), as the SDK's check reads it."""
    types = {part.split(b";")[0].strip().lower() for part in accept.split(b",")}
    if b"*/*" in types:
        return True
    return bool(types & {b"application/json", b"application/*"}) and bool(types & {b"text/event-stream", b"text/*"})


class JsonFirst:
    """ASGI middleware in front of a `JsonFirstSessionManager`; see the module docstring.
    It needs the body whole (`BodyLimits` in front of it buffers it)."""

    def __init__(self, app: ASGIApp, *, keepalive_s: float = KEEPALIVE_S) -> None:
        self.app = app
        self.keepalive_s = keepalive_s

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope.get("method") != "POST":
            await self.app(scope, receive, send)
            return
        first = await receive()
        body = first.get("body", b"") if first["type"] == "http.request" and not first.get("more_body") else None
        if body is None or not answers_with_json(scope, body):
            await self.app(scope, replaying(first, receive), send)
            return
        exchange = _Exchange(send, scope, self.keepalive_s)
        token = _JSON_MODE.set(True)
        try:
            await exchange.run(self.app, scope, body, receive)
        finally:
            _JSON_MODE.reset(token)


class _Exchange:
    """One JSON-mode call: watched for a disconnect once it runs past `WATCH_AFTER_S` (a call
    that ends sooner costs one timer, not a task), committed to SSE if it runs long."""

    def __init__(self, send: Send, scope: Scope, keepalive_s: float) -> None:
        self._send = send
        self._scope = scope
        self._keepalive_s = keepalive_s
        self._started = False  # the app's own response start went out: it owns the wire
        self._finished = False  # the response's last byte is on its way: nothing to cancel or ping
        self._streaming = False  # committed to SSE by a ping: the response goes as an event
        self._chunks: list[bytes] = []
        self._lock = asyncio.Lock()  # between the pinger and the app, once pings may start
        self._tasks: list[asyncio.Task[None]] = []
        self._timers: list[asyncio.TimerHandle] = []

    async def run(self, app: ASGIApp, scope: Scope, body: bytes, receive: Receive) -> None:
        gone = asyncio.Event()

        async def rest() -> Message:  # the app reads the body, then at most a disconnect
            await gone.wait()
            return {"type": "http.disconnect"}

        with anyio.CancelScope() as cancel:
            loop = asyncio.get_running_loop()
            self._timers.append(loop.call_later(min(WATCH_AFTER_S, self._keepalive_s), self._start_watching,
                                                receive, cancel, gone))
            try:
                await app(scope, replaying({"type": "http.request", "body": body, "more_body": False}, rest), self.send)
            finally:
                self._finished = True
                for timer in self._timers:
                    timer.cancel()
                for task in self._tasks:
                    task.cancel()

    def _start_watching(self, receive: Receive, cancel: anyio.CancelScope, gone: asyncio.Event) -> None:
        if self._finished:
            return
        loop = asyncio.get_running_loop()
        self._tasks.append(loop.create_task(self._watch(receive, cancel, gone)))
        delay = max(0.0, self._keepalive_s - WATCH_AFTER_S)
        self._timers.append(loop.call_later(delay, self._start_pinging))

    async def _watch(self, receive: Receive, cancel: anyio.CancelScope, gone: asyncio.Event) -> None:
        while (await receive())["type"] != "http.disconnect":
            pass
        gone.set()
        if not self._finished:  # the client left mid-call: cancel it, as the SDK's SSE mode does
            cancel.cancel()

    def _start_pinging(self) -> None:
        if not (self._finished or self._started):
            self._tasks.append(asyncio.get_running_loop().create_task(self._ping()))

    async def _ping(self) -> None:
        while True:
            async with self._lock:
                if self._finished or self._started:
                    return
                if not self._streaming:
                    self._streaming = True
                    await self._send({"type": "http.response.start", "status": 200, "headers": self._sse_headers()})
                await self._send({"type": "http.response.body", "body": _PING, "more_body": True})
            await asyncio.sleep(self._keepalive_s)

    def _sse_headers(self) -> list[tuple[bytes, bytes]]:
        session = [(name, value) for name, value in self._scope.get("headers", ()) if name == b"mcp-session-id"]
        return _SSE_HEADERS + session

    async def send(self, message: Message) -> None:
        """The app's response: passed through, or (once streaming) re-sent as one SSE event."""
        last = message["type"] == "http.response.body" and not message.get("more_body", False)
        if last:
            self._finished = True  # before the write: a disconnect seen after it cancels nothing
        if not self._streaming:  # no await between this check and the flag: the pinger sees it
            self._started = True
            await self._send(message)
            return
        if message["type"] != "http.response.body":
            return  # the app's JSON start: the SSE start went out already
        self._chunks.append(message.get("body", b""))
        if last:
            data = b"".join(self._chunks).decode("utf-8")
            lines = "".join(f"data: {line}\r\n" for line in data.splitlines())
            async with self._lock:
                await self._send({"type": "http.response.body", "body": f"event: message\r\n{lines}\r\n".encode(),
                                  "more_body": False})
