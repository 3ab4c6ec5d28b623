"""The LLM seam: messages in, a stream of typed events out.

Every backend (an OpenAI-compatible server, the embedded llama.cpp model, a
failover chain of those) implements `LLMBackend`. A turn is one call to
`stream(messages, tools)`, an async generator yielding, in this order:

* any number of `TextDelta` (text to speak, as the model produces it),
* then any `ToolCallRequested` (each one complete, arguments parsed),
* then exactly one `Finished`.

Failures raise `LLMError` (or a subclass below); a backend never yields an
"error event" and never returns ``None`` for failure.
"""

from __future__ import annotations

import base64
import json
from collections.abc import AsyncGenerator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, Protocol, runtime_checkable

from robovoice.errors import LLMError

if TYPE_CHECKING:
    from robovoice.config import BackendKind

Role = Literal["system", "user", "assistant", "tool"]
DeadlineName = Literal["connect", "first_token", "idle", "total"]

# --- errors ---------------------------------------------------------------------------


class DeadlineExceededError(LLMError):
    """A backend missed one of its `Deadlines`; names which one and where."""

    def __init__(self, deadline: DeadlineName, seconds: float, where: str) -> None:
        self.deadline = deadline
        self.seconds = seconds
        self.where = where
        super().__init__(f"{deadline} deadline of {seconds:g} s exceeded at {where}")


class LLMHTTPError(LLMError):
    """The server answered with an HTTP error status; carries its own message."""

    def __init__(self, status_code: int, server_message: str, url: str) -> None:
        self.status_code = status_code
        self.server_message = server_message
        self.url = url
        super().__init__(f"HTTP {status_code} from {url}: {server_message}")


# --- request side ---------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class TextPart:
    text: str

    def to_openai(self) -> dict[str, Any]:
        return {"type": "text", "text": self.text}


@dataclass(frozen=True, slots=True)
class AudioPart:
    """A WAV file (the whole file, header included) sent as OpenAI ``input_audio``."""

    wav_bytes: bytes

    def to_openai(self) -> dict[str, Any]:
        data = base64.b64encode(self.wav_bytes).decode("ascii")
        return {"type": "input_audio", "input_audio": {"data": data, "format": "wav"}}


ContentPart = TextPart | AudioPart


@dataclass(frozen=True, slots=True)
class ToolCall:
    """A tool call as it appears in the conversation history (assistant message)."""

    id: str
    name: str
    arguments: str  # the JSON text exactly as the model produced it

    def to_openai(self) -> dict[str, Any]:
        function = {"name": self.name, "arguments": self.arguments}
        return {"id": self.id, "type": "function", "function": function}


@dataclass(frozen=True, slots=True)
class ChatMessage:
    role: Role
    content: str | tuple[ContentPart, ...]
    tool_calls: tuple[ToolCall, ...] = ()
    tool_call_id: str | None = None  # for role "tool": which call this is the result of
    name: str | None = None

    @property
    def has_audio(self) -> bool:
        return not isinstance(self.content, str) and any(isinstance(p, AudioPart) for p in self.content)

    @property
    def text(self) -> str:
        """The text of the message, audio parts left out."""
        if isinstance(self.content, str):
            return self.content
        return "".join(p.text for p in self.content if isinstance(p, TextPart))

    def to_openai(self) -> dict[str, Any]:
        out: dict[str, Any] = {"role": self.role}
        if isinstance(self.content, str):
            out["content"] = self.content
        else:
            out["content"] = [part.to_openai() for part in self.content]
        if self.tool_calls:
            out["tool_calls"] = [call.to_openai() for call in self.tool_calls]
        if self.tool_call_id is not None:
            out["tool_call_id"] = self.tool_call_id
        if self.name is not None:
            out["name"] = self.name
        return out


@dataclass(frozen=True, slots=True)
class ToolSpec:
    """A callable function offered to the model; ``parameters`` is a JSON Schema object."""

    name: str
    description: str
    parameters: Mapping[str, Any] = field(default_factory=lambda: {"type": "object", "properties": {}})
    # declared read-only (MCP readOnlyHint): calling it changes nothing in the world; not sent to the model
    read_only: bool = False

    def to_openai(self) -> dict[str, Any]:
        function = {"name": self.name, "description": self.description, "parameters": dict(self.parameters)}
        return {"type": "function", "function": function}


def has_audio(messages: Sequence[ChatMessage]) -> bool:
    return any(m.has_audio for m in messages)


# --- events ---------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Usage:
    prompt_tokens: int
    completion_tokens: int
    # Prompt tokens served from a cache instead of evaluated (prefix reuse), when known.
    cached_prompt_tokens: int | None = None


@dataclass(frozen=True, slots=True)
class TextDelta:
    text: str


@dataclass(frozen=True, slots=True)
class ToolCallRequested:
    """A complete tool call. If the model's arguments were not a JSON object,
    ``arguments`` is empty and ``arguments_error`` says why: the caller should
    send that error back to the model as the tool result instead of calling."""

    id: str
    name: str
    arguments: dict[str, Any]
    raw_arguments: str
    arguments_error: str | None = None

    def to_history(self) -> ToolCall:
        return ToolCall(id=self.id, name=self.name, arguments=self.raw_arguments)


@dataclass(frozen=True, slots=True)
class Finished:
    reason: str  # "stop", "tool_calls", "length", ...
    usage: Usage | None = None


LLMEvent = TextDelta | ToolCallRequested | Finished


def tool_call_from_raw(call_id: str, name: str, raw_arguments: str) -> ToolCallRequested:
    """Build a `ToolCallRequested`, parsing the JSON arguments (empty means ``{}``)."""
    text = raw_arguments.strip()
    if not text:
        return ToolCallRequested(call_id, name, {}, raw_arguments)
    try:
        parsed = json.loads(text)
    except json.JSONDecodeError as exc:
        return ToolCallRequested(call_id, name, {}, raw_arguments, f"arguments are not valid JSON: {exc}")
    if not isinstance(parsed, dict):
        return ToolCallRequested(
            call_id, name, {}, raw_arguments, f"arguments must be a JSON object, got {type(parsed).__name__}"
        )
    return ToolCallRequested(call_id, name, parsed, raw_arguments)


# --- configuration --------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Deadlines:
    """Every wait on a model is bounded (seconds).

    Two ways a server keeps the user waiting, told apart:
    *unreachable* — connect: TCP/TLS connection; a refused connection fails at once and
    a failover chain moves on, only a silent (firewalled) host waits this long;
    *thinking* — first_token: from sending the request to the first content or tool-call
    chunk, while the server reads the prompt (a CPU server needs far longer than a GPU).
    idle: longest gap between chunks once streaming. total: one model call, start to end.
    """

    connect_s: float = 3.0
    first_token_s: float = 8.0
    idle_s: float = 10.0
    total_s: float = 60.0

# The embedded model: no connection; a CPU needs longer to its first token than a server
# (prefill of a long history on 2 cores). `first_token_s` of a `local = true` backend replaces it.
LOCAL_DEADLINES = Deadlines(connect_s=0.0, first_token_s=30.0, idle_s=10.0, total_s=120.0)

# Defaults by kind (docs/llm.md, "Deadlines"). local-cpu: a llama.cpp server on the robot's own
# CPU; a cold ~530-token prompt took 10-40 s on 2 loaded cores. edge-gpu: vLLM or llama.cpp on a
# GPU in the building, a few hundred ms when well, so 10 s means it is stuck. cloud: a hosted API,
# queueing included; TLS over the internet gets a longer connect.
DEADLINES_BY_KIND: Mapping[BackendKind, Deadlines] = {
    "local-cpu": Deadlines(connect_s=2.0, first_token_s=60.0, idle_s=20.0, total_s=120.0),
    "edge-gpu": Deadlines(connect_s=2.0, first_token_s=10.0, idle_s=10.0, total_s=60.0),
    "cloud": Deadlines(connect_s=5.0, first_token_s=15.0, idle_s=15.0, total_s=60.0),
}


# --- the seam -------------------------------------------------------------------------


@runtime_checkable
class LLMBackend(Protocol):
    """A streaming chat model with tools.

    ``stream`` is an async generator function: ``async def stream(...)`` with
    ``yield`` in the implementation. ``aclose`` releases connections/threads.
    """

    @property
    def name(self) -> str: ...

    @property
    def accepts_audio(self) -> bool:
        """True if the model takes `AudioPart` content (``input_audio``)."""
        ...

    def stream(self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]) -> AsyncGenerator[LLMEvent, None]: ...

    async def aclose(self) -> None: ...
