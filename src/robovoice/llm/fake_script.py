"""What `FakeOpenAIServer` answers: scripted replies, their pacing, and the server's quirks.

A script is a list of replies (`TextReply`, `ToolCallReply`, `ErrorReply`, `CallbackReply`);
each request takes the next one. `Quirks` make one server instance answer the way a particular
real server does instead of like vLLM (docs/llm.md, "Server quirks").
"""

from __future__ import annotations

import base64
import json
from collections.abc import Awaitable, Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

from robovoice.errors import LLMError

TextCallStyle = Literal["tool_calls", "hermes", "functions", "json", "mistral"]


@dataclass(frozen=True, slots=True)
class Quirks:
    """How a server instance departs from vLLM's wire format; each one as a real server does it."""

    no_finish_reason: bool = False  # finish_reason stays null; [DONE] ends the stream
    # how a ToolCallReply goes out: "tool_calls" (the standard), or as text in content, as servers
    # without a tool parser pass it through: "hermes" (<tool_call>{...}</tool_call>, Qwen2.5),
    # "functions" (functions.NAME:\n{...}, chatml-function-calling), "json" (a bare {"name", "arguments"}),
    # "mistral" ([TOOL_CALLS][...])
    tool_calls_as: TextCallStyle = "tool_calls"
    arguments_as_object: bool = False  # function.arguments is the JSON object itself, in one piece
    no_usage: bool = False  # no usage, even when stream_options.include_usage asks for it
    keep_alives: bool = False  # SSE comments (": ping - <date>", sse-starlette) between chunks and while waiting
    unknown_fields: bool = False  # fields this client does not know, at every level (llama.cpp "timings", ...)
    busy_status: int | None = None  # the first `busy_requests` requests get this status (429, 503) ...
    busy_retry_after: str | None = "1"  # ... with this Retry-After header (None: no header)
    busy_requests: int = 1
    # llama-cpp-python 0.3.36 chatml-function-calling: a streamed request answered by a tool call gets
    # an event stream with nothing but pings (the handler raises after the headers went out); the
    # same request without streaming is answered
    no_streamed_tool_calls: bool = False


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
    peer: str = ""  # the client's host:port: which connection the request came on

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
