"""The fake OpenAI server itself: recording, callbacks, errors, the raw wire format."""

from __future__ import annotations

import json

import httpx
import pytest

from robovoice.errors import LLMError
from robovoice.llm.fake_server import (
    CallbackReply,
    ErrorReply,
    FakeOpenAIServer,
    RecordedRequest,
    ScriptedCall,
    ScriptedReply,
    TextReply,
    ToolCallReply,
    reply_from_dict,
)

BODY = {"model": "fake-model", "messages": [{"role": "user", "content": "hi"}], "stream": True}


def data_lines(text: str) -> list[str]:
    return [line[len("data: ") :] for line in text.split("\n\n") if line.startswith("data: ")]


async def test_raw_stream_looks_like_vllm() -> None:
    reply = ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}, id="t1"),), arg_chunk_chars=8)
    async with FakeOpenAIServer([reply]) as srv, httpx.AsyncClient() as client:
        body = {**BODY, "stream_options": {"include_usage": True}}
        response = await client.post(f"{srv.base_url}/chat/completions", json=body)
    assert response.headers["content-type"].startswith("text/event-stream")
    lines = data_lines(response.text)
    assert lines[-1] == "[DONE]"
    chunks = [json.loads(line) for line in lines[:-1]]
    assert all(c["object"] == "chat.completion.chunk" and c["model"] == "fake-model" for c in chunks)
    assert chunks[0]["choices"][0]["delta"] == {"role": "assistant", "content": ""}
    assert chunks[1]["choices"][0]["delta"]["tool_calls"] == [
        {"id": "t1", "type": "function", "index": 0, "function": {"name": "navigate_to"}}
    ]
    pieces = [c["choices"][0]["delta"]["tool_calls"][0]["function"]["arguments"] for c in chunks[2:-2]]
    assert len(pieces) > 1 and "".join(pieces) == '{"target": "kitchen"}'
    assert chunks[-2]["choices"][0]["finish_reason"] == "tool_calls"
    assert chunks[-1]["choices"] == [] and chunks[-1]["usage"]["completion_tokens"] > 0


async def test_callback_decides_from_the_request() -> None:
    def sync_reply(request: RecordedRequest) -> ScriptedReply:
        return TextReply(f"you said {request.last_user_text}")

    async def async_reply(request: RecordedRequest) -> ScriptedReply:
        return ErrorReply(429, "slow down") if "twice" in request.last_user_text else TextReply("ok")

    script = [CallbackReply(sync_reply)]
    async with FakeOpenAIServer(script, default=CallbackReply(async_reply)) as srv:
        client = httpx.AsyncClient(base_url=srv.base_url)
        first = await client.post("/chat/completions", json=BODY)
        twice = {**BODY, "messages": [{"role": "user", "content": "twice"}]}
        second = await client.post("/chat/completions", json=twice)
        await client.aclose()
    chunks = [json.loads(x) for x in data_lines(first.text)[:-1]]
    assert "".join(c["choices"][0]["delta"].get("content", "") for c in chunks) == "you said hi"
    assert second.status_code == 429 and second.json()["error"]["message"] == "slow down"
    assert [r.last_user_text for r in srv.requests] == ["hi", "twice"]


async def test_bad_requests_and_exhausted_scripts() -> None:
    async with FakeOpenAIServer() as srv, httpx.AsyncClient(base_url=srv.base_url) as client:
        not_json = await client.post("/chat/completions", content=b"{nope")
        no_messages = await client.post("/chat/completions", json={"model": "m"})
        exhausted = await client.post("/chat/completions", json=BODY)
        models = await client.get("/models")
    assert not_json.status_code == 400 and "invalid JSON" in not_json.json()["error"]["message"]
    assert no_messages.status_code == 400
    assert exhausted.status_code == 500 and "script exhausted" in exhausted.json()["error"]["message"]
    assert models.json()["data"][0]["id"] == "fake-model"


async def test_non_streamed_completion() -> None:
    async with FakeOpenAIServer([TextReply("plain")]) as srv, httpx.AsyncClient(base_url=srv.base_url) as client:
        response = await client.post("/chat/completions", json={**BODY, "stream": False})
    assert response.json()["choices"][0]["message"] == {"role": "assistant", "content": "plain"}


def test_replies_from_json() -> None:
    assert reply_from_dict({"text": "hi"}) == TextReply("hi")
    assert reply_from_dict({"error": 503, "message": "busy"}) == ErrorReply(503, "busy")
    call = reply_from_dict({"tool_calls": [{"name": "stop_robot"}], "pacing": {"first_token_delay_s": 1}})
    assert isinstance(call, ToolCallReply) and call.calls[0].name == "stop_robot"
    assert call.pacing.first_token_delay_s == 1
    with pytest.raises(LLMError, match="unknown scripted reply"):
        reply_from_dict({"nothing": 1})


async def test_port_is_only_known_while_running() -> None:
    srv = FakeOpenAIServer()
    with pytest.raises(LLMError, match="not running"):
        _ = srv.base_url
