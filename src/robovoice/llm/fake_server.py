"""A real HTTP server that speaks OpenAI chat completions like vLLM, from a script.

    script = [TextReply("Hello!"), ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),))]
    async with FakeOpenAIServer(script) as srv:
        backend = OpenAICompatBackend(srv.base_url, srv.model)
        ...
        assert srv.requests[0].tool_names == ["navigate_to", ...]

Each request to ``POST /v1/chat/completions`` takes the next scripted reply
(or ``default`` once the script is used up). Streamed answers use vLLM's chunk
layout: a role chunk, ``delta.content`` pieces, tool calls as a first delta with
``id``/``type``/``function.name`` followed by ``function.arguments`` pieces,
a final chunk with ``finish_reason``, an optional usage chunk, ``data: [DONE]``.
One difference in timing only: the role chunk goes out at once (vLLM sends it
with the first token), so clients are tested not to take it for a token.
"""

from __future__ import annotations

import asyncio
import base64
import contextlib
import inspect
import json
import logging
import socket
import time
import uuid
from collections.abc import AsyncIterator, Awaitable, Callable, Iterable, Mapping
from dataclasses import dataclass, field
from types import TracebackType
from typing import Any

import uvicorn
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import JSONResponse, Response, StreamingResponse
from starlette.routing import Route

from robovoice.errors import LLMError

log = logging.getLogger(__name__)

# --- the script ---------------------------------------------------------------------


class StreamCut(ConnectionResetError):
    """Raised inside a streamed response to reset the connection mid-body (`Pacing.cut_hard`)."""


@dataclass(frozen=True, slots=True)
class Pacing:
    """When chunks go out. Stalls end early when the server shuts down."""

    headers_delay_s: float = 0.0  # before the HTTP response starts (an overloaded server)
    first_token_delay_s: float = 0.0  # after the role chunk, before the first token (prefill)
    stall_after_chunks: int | None = None  # stall after this many token chunks ...
    stall_s: float = 0.0  # ... for this long (mid-stream stall)
    chunk_interval_s: float = 0.0  # between token chunks
    cut_after_chunks: int | None = None  # the server closes the stream after this many token chunks ...
    cut_hard: bool = False  # ... without the final chunk and [DONE]; hard: the connection is reset mid-body


@dataclass(frozen=True, slots=True)
class TextReply:
    text: str
    chunk_chars: int = 4
    pacing: Pacing = Pacing()
    finish_reason: str = "stop"


@dataclass(frozen=True, slots=True)
class ScriptedCall:
    name: str
    arguments: str | Mapping[str, Any] = field(default_factory=dict)  # a str is sent verbatim
    id: str | None = None

    @property
    def arguments_json(self) -> str:
        return self.arguments if isinstance(self.arguments, str) else json.dumps(dict(self.arguments))


@dataclass(frozen=True, slots=True)
class ToolCallReply:
    calls: tuple[ScriptedCall, ...]
    text: str = ""  # content streamed before the calls
    arg_chunk_chars: int = 5
    pacing: Pacing = Pacing()


@dataclass(frozen=True, slots=True)
class ErrorReply:
    status: int
    message: str
    error_type: str = "BadRequestError"


@dataclass(frozen=True, slots=True)
class CallbackReply:
    """Decides the reply from the request (sync or async function)."""

    fn: Callable[[RecordedRequest], ScriptedReply | Awaitable[ScriptedReply]]


ScriptedReply = TextReply | ToolCallReply | ErrorReply | CallbackReply
ConcreteReply = TextReply | ToolCallReply | ErrorReply


@dataclass(frozen=True, slots=True)
class RecordedRequest:
    path: str
    headers: Mapping[str, str]
    body: Mapping[str, Any]

    @property
    def messages(self) -> list[dict[str, Any]]:
        return list(self.body.get("messages") or [])

    @property
    def tool_names(self) -> list[str]:
        return [t["function"]["name"] for t in self.body.get("tools") or []]

    @property
    def last_user_text(self) -> str:
        for message in reversed(self.messages):
            if message.get("role") == "user":
                content = message.get("content")
                if isinstance(content, str):
                    return content
                return "".join(p.get("text", "") for p in content or [] if p.get("type") == "text")
        return ""

    def audio_inputs(self) -> list[tuple[str, bytes]]:
        """Every ``input_audio`` part as (format, decoded bytes)."""
        found: list[tuple[str, bytes]] = []
        for message in self.messages:
            content = message.get("content")
            for part in content if isinstance(content, list) else []:
                if part.get("type") == "input_audio":
                    audio = part["input_audio"]
                    found.append((str(audio.get("format")), base64.b64decode(audio["data"], validate=True)))
        return found


def reply_from_dict(data: Mapping[str, Any]) -> ConcreteReply:
    """A reply from JSON, for scripts in files: ``{"text": ...}``, ``{"tool_calls": [{"name", "arguments"}]}``
    or ``{"error": status, "message": ...}``; optional ``"pacing": {...}``."""
    pacing = Pacing(**data.get("pacing", {}))
    if "error" in data:
        return ErrorReply(int(data["error"]), str(data.get("message", "error")))
    if "tool_calls" in data:
        calls = tuple(ScriptedCall(c["name"], c.get("arguments", {}), c.get("id")) for c in data["tool_calls"])
        return ToolCallReply(calls, text=str(data.get("text", "")), pacing=pacing)
    if "text" in data:
        return TextReply(str(data["text"]), pacing=pacing)
    raise LLMError(f"unknown scripted reply {dict(data)!r}: use text, tool_calls or error")


# --- the server ---------------------------------------------------------------------


def _chunks(text: str, size: int) -> list[str]:
    size = max(1, size)
    return [text[i : i + size] for i in range(0, len(text), size)]


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
    ) -> None:
        self._script: list[ScriptedReply] = list(script)
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
        recorded = RecordedRequest(request.url.path, dict(request.headers), fields)
        self.requests.append(recorded)
        if self.api_key is not None and request.headers.get("authorization") != f"Bearer {self.api_key}":
            return _error(401, "Incorrect API key provided", "AuthenticationError")
        if not isinstance(body, dict) or not isinstance(body.get("messages"), list) or "model" not in body:
            return _error(400, "request needs 'model' and a list of 'messages'")
        reply = await self._next_reply(recorded)
        if isinstance(reply, ErrorReply):
            return _error(reply.status, reply.message, reply.error_type)
        await self._pause(reply.pacing.headers_delay_s)
        include_usage = bool((body.get("stream_options") or {}).get("include_usage"))
        if not body.get("stream"):
            return JSONResponse(self._completion(reply))
        return StreamingResponse(self._sse(reply, include_usage), media_type="text/event-stream")

    def _completion(self, reply: TextReply | ToolCallReply) -> dict[str, Any]:
        message: dict[str, Any] = {"role": "assistant", "content": reply.text or None}
        finish = "stop"
        if isinstance(reply, ToolCallReply):
            finish = "tool_calls"
            message["tool_calls"] = [
                {
                    "id": c.id or f"chatcmpl-tool-{uuid.uuid4().hex[:16]}",
                    "type": "function",
                    "function": {"name": c.name, "arguments": c.arguments_json},
                }
                for c in reply.calls
            ]
        else:
            finish = reply.finish_reason
        return {
            "id": f"chatcmpl-{uuid.uuid4().hex}",
            "object": "chat.completion",
            "created": int(time.time()),
            "model": self.model,
            "choices": [{"index": 0, "message": message, "logprobs": None, "finish_reason": finish}],
            "usage": {"prompt_tokens": 10, "completion_tokens": 5, "total_tokens": 15},
        }

    async def _sse(self, reply: TextReply | ToolCallReply, include_usage: bool) -> AsyncIterator[bytes]:
        completion_id = f"chatcmpl-{uuid.uuid4().hex}"
        created = int(time.time())

        def event(choices: list[dict[str, Any]], **extra: Any) -> bytes:
            data = {
                "id": completion_id,
                "object": "chat.completion.chunk",
                "created": created,
                "model": self.model,
                "choices": choices,
                **extra,
            }
            return f"data: {json.dumps(data)}\n\n".encode()

        def chunk(delta: dict[str, Any], finish: str | None = None) -> bytes:
            choice: dict[str, Any] = {"index": 0, "delta": delta, "logprobs": None, "finish_reason": finish}
            if finish is not None:
                choice["stop_reason"] = None
            return event([choice])

        deltas, finish = _deltas(reply)
        pacing = reply.pacing
        yield chunk({"role": "assistant", "content": ""})
        await self._pause(pacing.first_token_delay_s)
        for sent, delta in enumerate(deltas):
            if pacing.cut_after_chunks is not None and sent == pacing.cut_after_chunks:
                if pacing.cut_hard:
                    raise StreamCut(f"fake server: stream reset after {sent} chunks (scripted)")
                return
            if pacing.stall_after_chunks is not None and sent == pacing.stall_after_chunks:
                await self._pause(pacing.stall_s)
            elif sent:
                await self._pause(pacing.chunk_interval_s)
            yield chunk(delta)
        yield chunk({"content": ""}, finish)
        if include_usage:
            n = max(1, len(deltas))
            yield event([], usage={"prompt_tokens": 10, "total_tokens": 10 + n, "completion_tokens": n})
        yield b"data: [DONE]\n\n"


def _deltas(reply: TextReply | ToolCallReply) -> tuple[list[dict[str, Any]], str]:
    """The ``delta`` objects of a streamed reply (after the role chunk) and its finish reason."""
    if isinstance(reply, TextReply):
        return [{"content": piece} for piece in _chunks(reply.text, reply.chunk_chars)], reply.finish_reason
    deltas: list[dict[str, Any]] = [{"content": piece} for piece in _chunks(reply.text, 4)]
    for index, call in enumerate(reply.calls):
        call_id = call.id or f"chatcmpl-tool-{uuid.uuid4().hex[:16]}"
        head = {"id": call_id, "type": "function", "index": index, "function": {"name": call.name}}
        deltas.append({"tool_calls": [head]})
        for piece in _chunks(call.arguments_json, reply.arg_chunk_chars):
            deltas.append({"tool_calls": [{"index": index, "function": {"arguments": piece}}]})
    return deltas, "tool_calls"


def _error(status: int, message: str, error_type: str = "BadRequestError") -> Response:
    body = {"error": {"message": message, "type": error_type, "param": None, "code": status}}
    return JSONResponse(body, status_code=status)
