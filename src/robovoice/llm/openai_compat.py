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
``content`` (`text_calls`), and 429/503 with ``Retry-After`` (`retry_after`). A server that
sends an empty event stream for a request with tools (llama-cpp-python 0.3.36's
``chatml-function-calling`` cannot stream a tool call: it pings, then closes) is asked again
without streaming, and this backend's tool steps are not streamed from then on.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import AsyncGenerator, AsyncIterator, Awaitable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar, cast

import httpx

from robovoice.errors import LLMError
from robovoice.llm.base import (
    ChatMessage,
    DeadlineExceededError,
    DeadlineName,
    Deadlines,
    LLMEvent,
    LLMHTTPError,
    TextDelta,
    ToolSpec,
    has_audio,
)
from robovoice.llm.openai_wire import (
    TurnState,
    apply_chunk,
    error_message_from_body,
    events_from_completion,
    parse_sse_line,
)
from robovoice.llm.retry_after import RETRYABLE_STATUS, RetryAfterError, retry_after_seconds
from robovoice.llm.text_calls import TextCallParser

log = logging.getLogger(__name__)
_T = TypeVar("_T")


@dataclass(frozen=True, slots=True)
class _Phase:
    """The deadline currently running: its name, length and absolute end (monotonic)."""

    name: DeadlineName
    seconds: float
    at: float


class EmptyStreamError(LLMError):
    """The server accepted the request (HTTP 200) but its event stream ended with no data at all."""


def _unstreamed(body: Mapping[str, Any]) -> dict[str, Any]:
    out = {k: v for k, v in body.items() if k != "stream_options"}  # only allowed when streaming
    out["stream"] = False
    return out


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
        self.streams_tool_calls = True  # False once the server sent an empty stream for a request with tools
        self._headers = {"Accept": "text/event-stream"}
        if api_key:
            self._headers["Authorization"] = f"Bearer {api_key}"
        self._transport = transport
        self._client = self._new_client()

    def _new_client(self) -> httpx.AsyncClient:
        d = self.deadlines
        # httpx read timeout off: first-token/idle/total deadlines are enforced below.
        timeout = httpx.Timeout(connect=d.connect_s, read=None, write=d.connect_s, pool=d.connect_s)
        return httpx.AsyncClient(headers=self._headers, timeout=timeout, transport=self._transport)

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
        body = self.request_body(messages, tools)
        if tools and not self.streams_tool_calls:
            body = _unstreamed(body)
        try:
            async for event in self._answer(body, start, first, total_at, names):
                yield event
        except EmptyStreamError:
            if not tools or body["stream"] is False:
                raise
            log.warning("%s sent an empty event stream for a request with tools (a server that cannot "
                        "stream tool calls, e.g. llama-cpp-python's chatml-function-calling): asked again "
                        "without streaming, and so from now on", self.name)
            self.streams_tool_calls = False
            # a fresh connection: llama-cpp-python's server cannot read the next request on the one
            # whose handler failed (HTTP 400 "error parsing the body", then it drops the connection)
            stale, self._client = self._client, self._new_client()
            await stale.aclose()
            again = _Phase("first_token", d.first_token_s, min(time.monotonic() + d.first_token_s, total_at))
            async for event in self._answer(_unstreamed(body), start, again, total_at, names):
                yield event

    async def _answer(
        self, body: dict[str, Any], start: float, first: _Phase, total_at: float, names: Sequence[str]
    ) -> AsyncIterator[LLMEvent]:
        """One request and its answer's events, streamed or not (a server may ignore ``stream``)."""
        response = await self._open(body, first, total_at)
        try:
            if response.headers.get("content-type", "").startswith("application/json"):
                data = await self._bounded(response.aread(), first, total_at)
                for event in events_from_completion(data, self.url, names):
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
        state = TurnState()
        parser = TextCallParser(tool_names)  # holds back content that may be a call written as text
        done = False
        data_lines = 0
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
                data_lines += 1
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
        if not data_lines:
            raise EmptyStreamError(f"stream from {self.url} ended before any answer (no data, no [DONE]): "
                                   "the server failed after accepting the request; its log says why")
        rest, text_calls = parser.finish()
        if rest:
            yield TextDelta(rest)
        for event in state.final_events(self.url, text_calls, done=done):
            yield event

    async def aclose(self) -> None:
        await self._client.aclose()
