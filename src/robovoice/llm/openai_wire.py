"""Reading an OpenAI-compatible answer: SSE lines, ``chat.completion.chunk``s folded into a turn,
a non-streamed ``chat.completion``, an error body. Tolerant of real servers' quirks (docs/llm.md,
"Server quirks"): no finish reason after ``[DONE]``, arguments as an object, no usage, unknown fields,
comments and keep-alives, tool calls written as text (`text_calls`)."""

from __future__ import annotations

import json
import logging
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from robovoice.errors import LLMError
from robovoice.llm.base import Finished, LLMEvent, TextDelta, Usage, tool_call_from_raw
from robovoice.llm.text_calls import TextCall, TextCallParser

log = logging.getLogger(__name__)


@dataclass(slots=True)
class PartialCall:
    id: str = ""
    name: str = ""
    arguments: list[str] = field(default_factory=list)


@dataclass(slots=True)
class TurnState:
    """What a streamed answer has said so far."""

    calls: dict[int, PartialCall] = field(default_factory=dict)
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


def apply_chunk(chunk: Mapping[str, Any], state: TurnState) -> str:
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
        call = state.calls.setdefault(index, PartialCall())
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
    state = TurnState(finish_reason=str(finish_reason), usage=_usage_from(data.get("usage")))
    for index, raw in enumerate(message.get("tool_calls") or []):
        function = raw.get("function") or {}
        state.calls[index] = PartialCall(
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
