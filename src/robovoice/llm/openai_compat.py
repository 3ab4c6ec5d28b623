"""`OpenAICompatBackend`: chat completions over HTTP, streamed (SSE), with tools.

Speaks the wire format of vLLM, llama.cpp's server, Ollama and the cloud
providers: ``POST {base_url}/chat/completions`` with ``stream: true``; the
answer is ``data: {...}`` lines (``choices[0].delta.content`` and
``delta.tool_calls[i]`` whose ``function.arguments`` arrive in pieces), ended
by ``data: [DONE]``. Every wait is bounded by `Deadlines`; httpx's own read
timeout is off so that our deadlines (not the library's) decide.
"""

from __future__ import annotations

import asyncio
import json
import logging
import time
from collections.abc import AsyncGenerator, AsyncIterator, Awaitable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, TypeVar, cast

import httpx

from robovoice.errors import LLMError
from robovoice.llm.base import (
    ChatMessage,
    DeadlineExceededError,
    DeadlineName,
    Deadlines,
    Finished,
    LLMEvent,
    LLMHTTPError,
    TextDelta,
    ToolSpec,
    Usage,
    has_audio,
    tool_call_from_raw,
)

log = logging.getLogger(__name__)
_T = TypeVar("_T")


@dataclass(frozen=True, slots=True)
class _Phase:
    """The deadline currently running: its name, length and absolute end (monotonic)."""

    name: DeadlineName
    seconds: float
    at: float


@dataclass(slots=True)
class _PartialCall:
    id: str = ""
    name: str = ""
    arguments: list[str] = field(default_factory=list)


@dataclass(slots=True)
class _TurnState:
    """What a streamed answer has said so far."""

    calls: dict[int, _PartialCall] = field(default_factory=dict)
    finish_reason: str | None = None
    usage: Usage | None = None
    progress: int = 0  # chunks that carried model output (content, reasoning, calls, finish)

    def final_events(self, url: str) -> Iterator[LLMEvent]:
        """The assembled tool calls (in index order), then `Finished`."""
        if self.finish_reason is None:
            raise LLMError(f"stream from {url} ended without a finish reason")
        for index in sorted(self.calls):
            call = self.calls[index]
            if not call.name:
                raise LLMError(f"tool call #{index} from {url} has no function name")
            yield tool_call_from_raw(call.id or f"call_{index}", call.name, "".join(call.arguments))
        yield Finished(self.finish_reason, self.usage)


def error_message_from_body(body: bytes) -> str:
    """The server's message from an error body (OpenAI ``{"error": {...}}`` or vLLM's flat form)."""
    text = body.decode("utf-8", errors="replace").strip()
    try:
        data = json.loads(text)
    except json.JSONDecodeError:
        return text[:500] or "(empty body)"
    if isinstance(data, dict):
        err = data.get("error", data)
        if isinstance(err, dict) and "message" in err:
            return str(err["message"])
        if isinstance(err, str):
            return err
    return text[:500]


def _usage_from(raw: Any) -> Usage | None:
    if not isinstance(raw, dict):
        return None
    details = raw.get("prompt_tokens_details")
    cached = details.get("cached_tokens") if isinstance(details, dict) else None
    return Usage(
        prompt_tokens=int(raw.get("prompt_tokens") or 0),
        completion_tokens=int(raw.get("completion_tokens") or 0),
        cached_prompt_tokens=int(cached) if cached is not None else None,
    )


_MODEL_OUTPUT_KEYS = ("content", "tool_calls", "reasoning_content", "reasoning")


def apply_chunk(chunk: Mapping[str, Any], state: _TurnState) -> str:
    """Fold one ``chat.completion.chunk`` into ``state``; returns its text delta ('' if none)."""
    if chunk.get("error") or chunk.get("object") == "error":
        raise LLMError(f"server error in stream: {error_message_from_body(json.dumps(chunk).encode())}")
    usage = _usage_from(chunk.get("usage"))
    if usage is not None:
        state.usage = usage
    choices = chunk.get("choices") or []
    if not choices:
        return ""
    choice = choices[0]
    delta = choice.get("delta") or {}
    if choice.get("finish_reason"):
        state.finish_reason = str(choice["finish_reason"])
    # Anything the model produced (reasoning too, which is not spoken) shows it is alive.
    if choice.get("finish_reason") or any(delta.get(k) for k in _MODEL_OUTPUT_KEYS):
        state.progress += 1
    for raw_call in delta.get("tool_calls") or []:
        index = int(raw_call.get("index", len(state.calls)))
        call = state.calls.setdefault(index, _PartialCall())
        if raw_call.get("id"):
            call.id = str(raw_call["id"])
        function = raw_call.get("function") or {}
        name = function.get("name")
        if name and name != call.name:
            # Sent once by vLLM/OpenAI; a server that streams the name in pieces is appended.
            call.name = str(name) if not call.name else call.name + str(name)
        if function.get("arguments"):
            call.arguments.append(str(function["arguments"]))
    content = delta.get("content")
    return content if isinstance(content, str) else ""


def events_from_completion(body: bytes, url: str) -> Iterator[LLMEvent]:
    """Events from a non-streamed ``chat.completion`` (a server that ignored ``stream``)."""
    try:
        data = json.loads(body)
        message = data["choices"][0]["message"]
        finish_reason = data["choices"][0].get("finish_reason") or "stop"
    except (json.JSONDecodeError, KeyError, IndexError, TypeError) as exc:
        raise LLMError(f"unexpected completion body from {url}: {body[:200]!r}") from exc
    state = _TurnState(finish_reason=str(finish_reason), usage=_usage_from(data.get("usage")))
    for index, raw in enumerate(message.get("tool_calls") or []):
        function = raw.get("function") or {}
        state.calls[index] = _PartialCall(
            str(raw.get("id") or ""), str(function.get("name") or ""), [str(function.get("arguments") or "")]
        )
    content = message.get("content")
    if isinstance(content, str) and content:
        yield TextDelta(content)
    yield from state.final_events(url)


def parse_sse_line(line: str) -> Mapping[str, Any] | None:
    """One SSE line → a chunk; ``None`` for comments, blank and non-data lines;
    ``{"[DONE]": True}`` for the end marker."""
    if not line.startswith("data:"):
        return None  # blank separator, ": keep-alive" comment, "event:", "id:" ...
    payload = line[5:].strip()
    if payload == "[DONE]":
        return {"[DONE]": True}
    if not payload:
        return None
    try:
        data = json.loads(payload)
    except json.JSONDecodeError as exc:
        raise LLMError(f"malformed SSE data from server: {payload[:200]!r}") from exc
    if not isinstance(data, dict):
        raise LLMError(f"unexpected SSE data from server: {payload[:200]!r}")
    return data


class OpenAICompatBackend:
    """An OpenAI-compatible chat-completions endpoint (vLLM, llama.cpp, Ollama, cloud)."""

    def __init__(
        self,
        base_url: str,
        model: str,
        *,
        api_key: str | None = None,
        name: str | None = None,
        accepts_audio: bool = False,
        deadlines: Deadlines | None = None,
        extra_body: Mapping[str, Any] | None = None,
        temperature: float | None = 0.0,
        include_usage: bool = True,
        transport: httpx.AsyncBaseTransport | None = None,
    ) -> None:
        self.base_url = base_url.rstrip("/")
        self.url = f"{self.base_url}/chat/completions"
        self.model = model
        self.name = name or f"{model}@{self.base_url}"
        self.accepts_audio = accepts_audio
        self.deadlines = deadlines or Deadlines()
        self.extra_body = dict(extra_body or {})
        self.temperature = temperature
        self.include_usage = include_usage
        headers = {"Accept": "text/event-stream"}
        if api_key:
            headers["Authorization"] = f"Bearer {api_key}"
        d = self.deadlines
        # httpx read timeout off: first-token/idle/total deadlines are enforced below.
        timeout = httpx.Timeout(connect=d.connect_s, read=None, write=d.connect_s, pool=d.connect_s)
        self._client = httpx.AsyncClient(headers=headers, timeout=timeout, transport=transport)

    def __repr__(self) -> str:
        return f"OpenAICompatBackend({self.base_url!r}, model={self.model!r})"

    def request_body(self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]) -> dict[str, Any]:
        body: dict[str, Any] = {
            "model": self.model,
            "messages": [m.to_openai() for m in messages],
            "stream": True,
        }
        if tools:
            body["tools"] = [t.to_openai() for t in tools]
            body["tool_choice"] = "auto"
        if self.temperature is not None:
            body["temperature"] = self.temperature
        if self.include_usage:
            body["stream_options"] = {"include_usage": True}
        body.update(self.extra_body)
        return body

    async def stream(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]
    ) -> AsyncGenerator[LLMEvent, None]:
        if has_audio(messages) and not self.accepts_audio:
            raise LLMError(f"{self.name} does not accept audio input (accepts_audio is off)")
        d = self.deadlines
        start = time.monotonic()
        total_at = start + d.total_s
        first = _Phase("first_token", d.first_token_s, min(start + d.first_token_s, total_at))
        request = self._client.build_request("POST", self.url, json=self.request_body(messages, tools))
        response = await self._send(request, first, total_at)
        try:
            if response.status_code >= 400:
                body = await self._bounded(response.aread(), first, total_at)
                raise LLMHTTPError(response.status_code, error_message_from_body(body), self.url)
            if response.headers.get("content-type", "").startswith("application/json"):
                body = await self._bounded(response.aread(), first, total_at)
                for event in events_from_completion(body, self.url):
                    yield event
                return
            async for event in self._events(response, start, first, total_at):
                yield event
        finally:
            await response.aclose()

    async def _send(self, request: httpx.Request, first: _Phase, total_at: float) -> httpx.Response:
        try:
            return await self._bounded(self._client.send(request, stream=True), first, total_at)
        except httpx.TimeoutException as exc:  # ConnectTimeout, or the pool/write timeouts
            raise DeadlineExceededError("connect", self.deadlines.connect_s, self.url) from exc
        except httpx.HTTPError as exc:
            raise LLMError(f"cannot reach {self.url}: {type(exc).__name__}: {exc}") from exc

    async def _bounded(self, awaitable: Awaitable[_T], phase: _Phase, total_at: float) -> _T:
        """Await with the earlier of the phase deadline and the turn's total deadline."""
        at = min(phase.at, total_at)
        loop = asyncio.get_running_loop()
        try:
            async with asyncio.timeout_at(loop.time() + (at - time.monotonic())):
                return await awaitable
        except TimeoutError as exc:
            if total_at <= phase.at:
                raise DeadlineExceededError("total", self.deadlines.total_s, self.url) from exc
            raise DeadlineExceededError(phase.name, phase.seconds, self.url) from exc

    async def _events(
        self, response: httpx.Response, start: float, first: _Phase, total_at: float
    ) -> AsyncIterator[LLMEvent]:
        idle_s = self.deadlines.idle_s
        state = _TurnState()
        lines = cast(AsyncGenerator[str, None], response.aiter_lines())  # an async generator
        phase = first
        try:
            while True:
                try:
                    line = await self._bounded(anext(lines), phase, total_at)
                except StopAsyncIteration:
                    break
                except httpx.HTTPError as exc:
                    raise LLMError(f"stream from {self.url} broke: {type(exc).__name__}: {exc}") from exc
                chunk = parse_sse_line(line)
                if chunk is None:
                    continue
                if "[DONE]" in chunk:
                    break
                progress = state.progress
                text = apply_chunk(chunk, state)
                if state.progress > progress:
                    if phase is first:
                        log.debug("%s: first token after %.3f s", self.name, time.monotonic() - start)
                    phase = _Phase("idle", idle_s, time.monotonic() + idle_s)
                if text:
                    yield TextDelta(text)
        finally:
            await lines.aclose()
        for event in state.final_events(self.url):
            yield event

    async def aclose(self) -> None:
        await self._client.aclose()
