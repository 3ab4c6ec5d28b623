"""`OpenAICompatBackend`: chat completions over HTTP, streamed (SSE), with tools.

Speaks the wire format of vLLM, llama.cpp's server, Ollama and the cloud
providers: ``POST {base_url}/chat/completions`` with ``stream: true``; the
answer is ``data: {...}`` lines (``choices[0].delta.content`` and
``delta.tool_calls[i]`` whose ``function.arguments`` arrive in pieces), ended
by ``data: [DONE]``. Every wait is bounded by `Deadlines`; httpx's own read
timeout is off so that our deadlines (not the library's) decide.

Real servers' quirks are tolerated (docs/llm.md, "Server quirks"): a stream that ends with
``[DONE]`` but no ``finish_reason`` (llama-cpp-python), arguments sent as a JSON object, no
``usage``, unknown fields, SSE comments and keep-alives, tool calls written as text in
``content`` (`text_calls`), and 429/503 with ``Retry-After`` (`retry_after`).
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
from robovoice.llm.retry_after import RETRYABLE_STATUS, RetryAfterError, retry_after_seconds
from robovoice.llm.text_calls import TextCall, TextCallParser

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

    def final_events(self, url: str, text_calls: Sequence[TextCall] = (), *, done: bool = True) -> Iterator[LLMEvent]:
        """The assembled tool calls (in index order), those written as text, then `Finished`.
        `done`: the stream ended with ``[DONE]`` (so a missing finish reason is a quirk, not a cut)."""
        reason = self.finish_reason
        if reason is None:
            if not done:  # no finish reason and no [DONE]: the answer may have been cut short
                raise LLMError(f"stream from {url} ended without a finish reason or [DONE] (cut short?)")
            reason = "tool_calls" if self.calls or text_calls else "stop"
            log.debug("stream from %s ended with [DONE] but no finish reason; taken as %r", url, reason)
        for index in sorted(self.calls):
            call = self.calls[index]
            if not call.name:
                raise LLMError(f"tool call #{index} from {url} has no function name")
            yield tool_call_from_raw(call.id or f"call_{index}", call.name, "".join(call.arguments))
        for index, text_call in enumerate(text_calls, start=len(self.calls)):
            yield tool_call_from_raw(f"call_{index}", text_call.name, text_call.arguments)
        if text_calls and reason == "stop":  # the server did not know its text was a call
            reason = "tool_calls"
        yield Finished(reason, self.usage)


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
        call.arguments.append(_arguments_text(function.get("arguments")))
    content = delta.get("content")
    return content if isinstance(content, str) else ""


def _arguments_text(raw: Any) -> str:
    """Arguments as JSON text: some servers send the object itself instead of a JSON string."""
    if raw is None:
        return ""
    return json.dumps(raw) if isinstance(raw, dict | list) else str(raw)


def events_from_completion(body: bytes, url: str, tool_names: Sequence[str] = ()) -> Iterator[LLMEvent]:
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
            str(raw.get("id") or ""), str(function.get("name") or ""), [_arguments_text(function.get("arguments"))]
        )
    content = message.get("content")
    parser = TextCallParser(tool_names)
    text = parser.feed(content) if isinstance(content, str) else ""
    rest, text_calls = parser.finish()
    if text + rest:
        yield TextDelta(text + rest)
    yield from state.final_events(url, text_calls)


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
        names = [t.name for t in tools]
        response = await self._open(self.request_body(messages, tools), first, total_at)
        try:
            if response.headers.get("content-type", "").startswith("application/json"):
                body = await self._bounded(response.aread(), first, total_at)
                for event in events_from_completion(body, self.url, names):
                    yield event
                return
            async for event in self._events(response, start, first, total_at, names):
                yield event
        finally:
            await response.aclose()

    async def _open(self, body: dict[str, Any], first: _Phase, total_at: float) -> httpx.Response:
        """Send the request; a 2xx response, open. A 429/503 whose ``Retry-After`` fits in what is
        left of the first-token deadline is retried once; any other error status is raised."""
        for attempt in (1, 2):
            response = await self._send(self._client.build_request("POST", self.url, json=body), first, total_at)
            if response.status_code < 400:
                return response
            try:
                message = error_message_from_body(await self._bounded(response.aread(), first, total_at))
            finally:
                await response.aclose()
            status = response.status_code
            wait = retry_after_seconds(response.headers.get("retry-after")) if status in RETRYABLE_STATUS else None
            if wait is None:
                raise LLMHTTPError(status, message, self.url)
            if attempt == 2 or wait >= min(first.at, total_at) - time.monotonic():
                raise RetryAfterError(status, message, self.url, wait)
            log.info("%s: HTTP %d, retrying once after %g s (Retry-After)", self.name, status, wait)
            await asyncio.sleep(wait)
        raise AssertionError("unreachable: the second attempt returns or raises")

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
        self, response: httpx.Response, start: float, first: _Phase, total_at: float, tool_names: Sequence[str]
    ) -> AsyncIterator[LLMEvent]:
        idle_s = self.deadlines.idle_s
        state = _TurnState()
        parser = TextCallParser(tool_names)  # holds back content that may be a call written as text
        done = False
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
                    done = True
                    break
                progress = state.progress
                text = apply_chunk(chunk, state)
                if state.progress > progress:
                    if phase is first:
                        log.debug("%s: first token after %.3f s", self.name, time.monotonic() - start)
                    phase = _Phase("idle", idle_s, time.monotonic() + idle_s)
                released = parser.feed(text) if text else ""
                if released:
                    yield TextDelta(released)
        finally:
            await lines.aclose()
        rest, text_calls = parser.finish()
        if rest:
            yield TextDelta(rest)
        for event in state.final_events(self.url, text_calls, done=done):
            yield event

    async def aclose(self) -> None:
        await self._client.aclose()
