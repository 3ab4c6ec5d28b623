"""How `FakeOpenAIServer` puts a scripted reply on the wire: vLLM's layout, or a real server's quirks.

Streamed answers: a role chunk, ``delta.content`` pieces, tool calls as a first delta with
``id``/``type``/``function.name`` followed by ``function.arguments`` pieces, a final chunk with
``finish_reason``, an optional usage chunk, ``data: [DONE]``. `Quirks` change that the way the
server they are named after does.
"""

from __future__ import annotations

import json
import time
import uuid
from collections.abc import AsyncIterator, Callable
from email.utils import formatdate
from typing import Any

from robovoice.llm.fake_script import Quirks, ScriptedCall, StreamCut, TextReply, ToolCallReply

Pause = Callable[[float], AsyncIterator[bytes]]  # waits that long, yielding keep-alives if the quirk asks

_UNKNOWN_TOP = {"system_fingerprint": "fp_fake", "service_tier": None, "usage": None,
                "timings": {"prompt_n": 10, "predicted_ms": 1.5}}
_UNKNOWN_CHOICE = {"matched_stop": None, "x_vendor": {"spec_decode": False}}
_UNKNOWN_DELTA = {"reasoning_content": None, "refusal": None}


def chunks(text: str, size: int) -> list[str]:
    size = max(1, size)
    return [text[i : i + size] for i in range(0, len(text), size)]


def keep_alive() -> bytes:
    """An SSE comment the way sse-starlette (llama-cpp-python's server) pings, and a bare one."""
    return f": ping - {formatdate(usegmt=True)}\r\n\r\n:\n\n".encode()


async def failed_stream() -> AsyncIterator[bytes]:
    """An event stream that ends before any data (`Quirks.no_streamed_tool_calls`)."""
    yield keep_alive()


def _call_id(call: ScriptedCall) -> str:
    return call.id or f"chatcmpl-tool-{uuid.uuid4().hex[:16]}"


def _arguments(call: ScriptedCall, quirks: Quirks) -> Any:
    if quirks.arguments_as_object and not isinstance(call.arguments, str):
        return dict(call.arguments)
    return call.arguments_json


def calls_as_text(calls: tuple[ScriptedCall, ...], style: str) -> str:
    """Tool calls written in `content` the way a server without a tool parser passes them through."""
    def obj(call: ScriptedCall) -> str:  # a str argument is embedded verbatim (may be broken JSON)
        return f'{{"name": {json.dumps(call.name)}, "arguments": {call.arguments_json or "{}"}}}'

    if style == "hermes":
        return "\n".join(f"<tool_call>\n{obj(c)}\n</tool_call>" for c in calls)
    if style == "functions":  # an empty str argument gives the bare head llama-cpp-python sends
        return "\n".join(f"functions.{c.name}:" + (f"\n{c.arguments_json}" if c.arguments_json else "") for c in calls)
    if style == "json":
        return obj(calls[0]) if len(calls) == 1 else "[" + ", ".join(obj(c) for c in calls) + "]"
    if style == "mistral":
        return "[TOOL_CALLS][" + ", ".join(obj(c) for c in calls) + "]"
    raise ValueError(f"unknown tool_calls_as style {style!r}")


def completion(model: str, reply: TextReply | ToolCallReply, quirks: Quirks) -> dict[str, Any]:
    """A non-streamed ``chat.completion`` body."""
    text = reply.text
    message: dict[str, Any] = {"role": "assistant"}
    finish: str | None = reply.finish_reason if isinstance(reply, TextReply) else "tool_calls"
    if isinstance(reply, ToolCallReply):
        if quirks.tool_calls_as == "tool_calls":
            message["tool_calls"] = [
                {"id": _call_id(c), "type": "function",
                 "function": {"name": c.name, "arguments": _arguments(c, quirks)}}
                for c in reply.calls
            ]
        else:
            text = (text + "\n" if text else "") + calls_as_text(reply.calls, quirks.tool_calls_as)
            finish = "stop"
    message["content"] = text or None
    body: dict[str, Any] = {
        "id": f"chatcmpl-{uuid.uuid4().hex}",
        "object": "chat.completion",
        "created": int(time.time()),
        "model": model,
        "choices": [{"index": 0, "message": message, "logprobs": None,
                     "finish_reason": None if quirks.no_finish_reason else finish}],
    }
    if not quirks.no_usage:
        body["usage"] = {"prompt_tokens": 10, "completion_tokens": 5, "total_tokens": 15}
    if quirks.unknown_fields:
        body = {**_UNKNOWN_TOP, **body}
        body["choices"][0].update(_UNKNOWN_CHOICE)
    return body


def deltas(reply: TextReply | ToolCallReply, quirks: Quirks) -> tuple[list[dict[str, Any]], str]:
    """The ``delta`` objects of a streamed reply (after the role chunk) and its finish reason."""
    if isinstance(reply, TextReply):
        return [{"content": piece} for piece in chunks(reply.text, reply.chunk_chars)], reply.finish_reason
    if quirks.tool_calls_as != "tool_calls":
        text = (reply.text + "\n" if reply.text else "") + calls_as_text(reply.calls, quirks.tool_calls_as)
        return [{"content": piece} for piece in chunks(text, reply.arg_chunk_chars)], "stop"
    out: list[dict[str, Any]] = [{"content": piece} for piece in chunks(reply.text, 4)]
    for index, call in enumerate(reply.calls):
        function: dict[str, Any] = {"name": call.name}
        head = {"id": _call_id(call), "type": "function", "index": index, "function": function}
        out.append({"tool_calls": [head]})
        if quirks.arguments_as_object:  # the object whole, in the head chunk
            function["arguments"] = _arguments(call, quirks)
            continue
        for piece in chunks(call.arguments_json, reply.arg_chunk_chars):
            out.append({"tool_calls": [{"index": index, "function": {"arguments": piece}}]})
    return out, "tool_calls"


async def sse(
    model: str, reply: TextReply | ToolCallReply, quirks: Quirks, include_usage: bool, pause: Pause
) -> AsyncIterator[bytes]:
    """The streamed answer, as bytes. `pause` does the scripted waits."""
    completion_id = f"chatcmpl-{uuid.uuid4().hex}"
    created = int(time.time())

    def event(choices: list[dict[str, Any]], **extra: Any) -> bytes:
        data = {"id": completion_id, "object": "chat.completion.chunk", "created": created, "model": model,
                "choices": choices, **extra}
        if quirks.unknown_fields:
            data = {**_UNKNOWN_TOP, **data}
        return f"data: {json.dumps(data)}\n\n".encode()

    def chunk(delta: dict[str, Any], finish: str | None = None) -> bytes:
        if quirks.unknown_fields:
            delta = {**_UNKNOWN_DELTA, **delta}
        if quirks.no_finish_reason:
            finish = None
        choice: dict[str, Any] = {"index": 0, "delta": delta, "logprobs": None, "finish_reason": finish}
        if finish is not None:
            choice["stop_reason"] = None
        if quirks.unknown_fields:
            choice.update(_UNKNOWN_CHOICE)
        return event([choice])

    out, finish = deltas(reply, quirks)
    pacing = reply.pacing
    if quirks.keep_alives:
        yield keep_alive()
    yield chunk({"role": "assistant", "content": ""})
    async for ping in pause(pacing.first_token_delay_s):
        yield ping
    for sent, delta in enumerate(out):
        if pacing.cut_after_chunks is not None and sent == pacing.cut_after_chunks:
            if pacing.cut_hard:
                raise StreamCut(f"fake server: stream reset after {sent} chunks (scripted)")
            return
        wait = 0.0
        if pacing.stall_after_chunks is not None and sent == pacing.stall_after_chunks:
            wait = pacing.stall_s
        elif sent:
            wait = pacing.chunk_interval_s
        async for ping in pause(wait):
            yield ping
        if quirks.keep_alives:
            yield keep_alive()
        yield chunk(delta)
    yield chunk({"content": ""}, finish)
    if include_usage and not quirks.no_usage:
        n = max(1, len(out))
        yield event([], usage={"prompt_tokens": 10, "total_tokens": 10 + n, "completion_tokens": n})
    yield b"data: [DONE]\n\n"
