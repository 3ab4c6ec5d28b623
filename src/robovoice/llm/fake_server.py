"""A real HTTP server that speaks OpenAI chat completions like vLLM, from a script.

    script = [TextReply("Hello!"), ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),))]
    async with FakeOpenAIServer(script) as srv:
        backend = OpenAICompatBackend(srv.base_url, srv.model)
        ...
        assert srv.requests[0].tool_names == ["navigate_to", ...]

Each request to ``POST /v1/chat/completions`` takes the next scripted reply
(or ``default`` once the script is used up; the types are in `fake_script`).
Streamed answers use vLLM's chunk layout (`fake_wire`); ``quirks=Quirks(...)``
makes the instance answer like another real server instead (llama-cpp-python's
missing finish reason, tool calls as text, a busy 429/503 with Retry-After, ...).
One difference in timing only: the role chunk goes out at once (vLLM sends it
with the first token), so clients are tested not to take it for a token.
"""

from __future__ import annotations

import asyncio
import contextlib
import inspect
import json
import logging
import socket
import time
from collections.abc import AsyncIterator, Iterable
from types import TracebackType

import uvicorn
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import JSONResponse, Response, StreamingResponse
from starlette.routing import Route

from robovoice.errors import LLMError
from robovoice.llm import fake_wire
from robovoice.llm.fake_script import (
    CallbackReply,
    ConcreteReply,
    ErrorReply,
    Pacing,
    Quirks,
    RecordedRequest,
    ScriptedCall,
    ScriptedReply,
    StreamCut,
    TextCallStyle,
    TextReply,
    ToolCallReply,
    reply_from_dict,
)

__all__ = [  # the script types are used from here, beside the server
    "CallbackReply", "ConcreteReply", "ErrorReply", "FakeOpenAIServer", "Pacing", "Quirks", "RecordedRequest",
    "ScriptedCall", "ScriptedReply", "StreamCut", "TextCallStyle", "TextReply", "ToolCallReply", "reply_from_dict",
]

log = logging.getLogger(__name__)
# --- the server ---------------------------------------------------------------------


class FakeOpenAIServer:
    """Serves the script on 127.0.0.1 (an ephemeral port unless given) while entered."""

    def __init__(
        self,
        script: Iterable[ScriptedReply] = (),
        *,
        default: ScriptedReply | None = None,
        model: str = "fake-model",
        api_key: str | None = None,
        host: str = "127.0.0.1",
        port: int = 0,
        quirks: Quirks | None = None,
    ) -> None:
        self._script: list[ScriptedReply] = list(script)
        self.quirks = quirks or Quirks()  # may be changed between requests
        self.busy_sent = 0  # requests answered with quirks.busy_status
        self.default = default
        self.model = model
        self.api_key = api_key
        self.requests: list[RecordedRequest] = []
        self._host = host
        self._port = port
        self._closing = asyncio.Event()
        self._server: uvicorn.Server | None = None
        self._task: asyncio.Task[None] | None = None

    @property
    def port(self) -> int:
        if self._server is None:
            raise LLMError("FakeOpenAIServer is not running")
        return self._port

    @property
    def base_url(self) -> str:
        return f"http://{self._host}:{self.port}/v1"

    def push(self, *replies: ScriptedReply) -> None:
        self._script.extend(replies)

    # -- lifecycle --

    async def __aenter__(self) -> FakeOpenAIServer:
        app = Starlette(
            routes=[
                Route("/v1/chat/completions", self._chat, methods=["POST"]),
                Route("/v1/models", self._models, methods=["GET"]),
                Route("/health", self._health, methods=["GET"]),
            ]
        )
        config = uvicorn.Config(app, log_level="warning", access_log=False, lifespan="off", timeout_graceful_shutdown=2)
        sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM, socket.IPPROTO_TCP)  # asyncio: TCP_NODELAY
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((self._host, self._port))
        sock.listen(64)  # clients can connect (queued) before uvicorn starts accepting
        self._port = sock.getsockname()[1]
        self._closing = asyncio.Event()
        self._server = uvicorn.Server(config)
        self._task = asyncio.create_task(self._server.serve(sockets=[sock]), name=f"fake-llm:{self._port}")
        deadline = time.monotonic() + 10.0
        while not self._server.started:
            if self._task.done():
                await self._task  # re-raises why it stopped
                raise LLMError("fake LLM server stopped during start-up")
            if time.monotonic() > deadline:
                await self._stop()
                raise LLMError("fake LLM server did not start within 10 s")
            await asyncio.sleep(0.005)
        log.debug("fake LLM server on %s", self.base_url)
        return self

    async def __aexit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        await self._stop()

    async def _stop(self) -> None:
        self._closing.set()
        if self._server is not None:
            self._server.should_exit = True
        if self._task is not None:
            await self._task
            self._task = None

    async def _pause(self, seconds: float) -> None:
        if seconds > 0:
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(self._closing.wait(), seconds)

    async def _pause_pinging(self, seconds: float) -> AsyncIterator[bytes]:
        """Wait `seconds`, sending an SSE keep-alive every 0.1 s if the quirk asks for them."""
        if not self.quirks.keep_alives:
            await self._pause(seconds)
            return
        end = time.monotonic() + seconds
        while (left := end - time.monotonic()) > 0 and not self._closing.is_set():
            await self._pause(min(0.1, left))
            yield fake_wire.keep_alive()

    # -- handlers --

    async def _health(self, request: Request) -> Response:
        return JSONResponse({"status": "ok"})

    async def _models(self, request: Request) -> Response:
        return JSONResponse({"object": "list", "data": [{"id": self.model, "object": "model"}]})

    async def _next_reply(self, recorded: RecordedRequest) -> ConcreteReply:
        if self._script:
            reply = self._script.pop(0)
        elif self.default is not None:
            reply = self.default
        else:
            return ErrorReply(500, "fake server: script exhausted", "InternalServerError")
        if isinstance(reply, CallbackReply):
            decided = reply.fn(recorded)
            reply = await decided if inspect.isawaitable(decided) else decided
            if isinstance(reply, CallbackReply):
                return ErrorReply(500, "fake server: a callback returned a callback", "InternalServerError")
        return reply

    async def _chat(self, request: Request) -> Response:
        raw = await request.body()
        try:
            body = json.loads(raw)
        except json.JSONDecodeError as exc:
            return _error(400, f"invalid JSON body: {exc}")
        fields = body if isinstance(body, dict) else {}
        peer = f"{request.client.host}:{request.client.port}" if request.client is not None else ""
        recorded = RecordedRequest(request.url.path, dict(request.headers), fields, peer)
        self.requests.append(recorded)
        if self.api_key is not None and request.headers.get("authorization") != f"Bearer {self.api_key}":
            return _error(401, "Incorrect API key provided", "AuthenticationError")
        if not isinstance(body, dict) or not isinstance(body.get("messages"), list) or "model" not in body:
            return _error(400, "request needs 'model' and a list of 'messages'")
        quirks = self.quirks
        if quirks.busy_status is not None and self.busy_sent < quirks.busy_requests:
            self.busy_sent += 1  # a busy server does not take the request: the script is not used
            headers = {"Retry-After": quirks.busy_retry_after} if quirks.busy_retry_after is not None else {}
            return _error(quirks.busy_status, "server busy, try again later", "ServiceUnavailableError", headers)
        reply = await self._next_reply(recorded)
        if isinstance(reply, ErrorReply):
            return _error(reply.status, reply.message, reply.error_type)
        if quirks.no_streamed_tool_calls and body.get("stream") and isinstance(reply, ToolCallReply):
            self._script.insert(0, reply)  # the failed request consumed nothing: asked again, it is answered
            return StreamingResponse(fake_wire.failed_stream(), media_type="text/event-stream")
        await self._pause(reply.pacing.headers_delay_s)
        include_usage = bool((body.get("stream_options") or {}).get("include_usage"))
        if not body.get("stream"):
            return JSONResponse(fake_wire.completion(self.model, reply, quirks))
        stream = fake_wire.sse(self.model, reply, quirks, include_usage, self._pause_pinging)
        return StreamingResponse(stream, media_type="text/event-stream")


def _error(status: int, message: str, error_type: str = "BadRequestError",
           headers: dict[str, str] | None = None) -> Response:
    body = {"error": {"message": message, "type": error_type, "param": None, "code": status}}
    return JSONResponse(body, status_code=status, headers=headers)
