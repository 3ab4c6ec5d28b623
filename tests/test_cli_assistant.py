"""`robovoice chat` and `robovoice eval` as a user runs them (real processes)."""

from __future__ import annotations

import asyncio
import json
import os
import socket
import sys
import time
from pathlib import Path

import pytest

from robovoice.llm.fake_server import (
    CallbackReply,
    FakeOpenAIServer,
    RecordedRequest,
    ScriptedCall,
    ScriptedReply,
    TextReply,
    ToolCallReply,
)

from .distributed.helpers import Child, robovoice

ROBOVOICE = [sys.executable, "-m", "robovoice.cli"]
DATA = Path(__file__).parent / "data" / "eval"
needs_model = pytest.mark.usefixtures("local_model_installed")  # tests/conftest.py: fails, never skips


def _dead_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


async def _run(*args: str, stdin: str = "", timeout: float = 240) -> tuple[int, str, str]:
    proc = await asyncio.create_subprocess_exec(
        *ROBOVOICE, *args, stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE,
        stderr=asyncio.subprocess.PIPE, env={**os.environ, "PYTHONUNBUFFERED": "1"})
    out, err = await asyncio.wait_for(proc.communicate(stdin.encode()), timeout)
    return proc.returncode or 0, out.decode(), err.decode()


async def test_chat_through_a_server_shows_calls_and_answers() -> None:
    script: list[ScriptedReply] = [ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),))]
    async with FakeOpenAIServer(script) as server:
        code, out, err = await _run("chat", "--robot", "sim", "--sim-speed", "50",
                                    "--llm", server.base_url, "--model", server.model,
                                    stdin="please drive to the kitchen\n")
    assert code == 0, err
    assert "→ navigate_to(target='kitchen')" in out
    assert "← navigate_to ok" in out and '"arrived": "kitchen"' in out
    assert "robot> I am in the kitchen now." in out  # the drive's success phrase


async def test_chat_with_nothing_reachable_says_the_fallback_within_the_deadline() -> None:
    start = time.monotonic()
    code, out, err = await _run("chat", "--robot", "sim", "--llm", f"http://127.0.0.1:{_dead_port()}/v1#m",
                                stdin="hello\n")
    assert code == 0, err
    assert "robot> I can't reach my language model right now." in out
    assert "! no language model answered" in out and "Traceback" not in err
    assert time.monotonic() - start < 30


async def test_eval_json_summary_with_a_scripted_model() -> None:
    def reply(request: RecordedRequest) -> ToolCallReply | TextReply:
        if request.messages[-1]["role"] == "tool":
            return TextReply("Done.")
        text = request.last_user_text.lower()
        if "kitchen" in text:
            return ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),))
        return TextReply("Hello!")

    async with FakeOpenAIServer([], default=CallbackReply(reply)) as server:
        code, out, err = await _run("eval", str(DATA / "text.jsonl"), "--robot", "sim", "--sim-speed", "50",
                                    "--only", "nav-kitchen-1", "--only", "chat-1", "--only", "proj-on-1",
                                    "--llm", server.base_url, "--model", server.model, "--json")
    assert code == 0, err
    summary = json.loads(out)
    assert summary["cases"] == 3 and summary["passed"] == 2 and summary["accuracy"] == pytest.approx(2 / 3, 0.01)
    by_id = {r["id"]: r for r in summary["results"]}
    assert by_id["nav-kitchen-1"]["passed"] and [(c["tool"], c["args"]) for c in by_id["nav-kitchen-1"]["calls"]] == [
        ("navigate_to", {"target": "kitchen"})]
    assert not by_id["proj-on-1"]["passed"] and by_id["proj-on-1"]["reply"] == "Hello!"
    assert summary["p50"] is not None and "first_token" in summary["stages"]


async def test_eval_of_a_missing_file_fails_cleanly() -> None:
    code, _, err = await _run("eval", "no/such/cases.jsonl")
    assert code == 1 and "cannot read case file" in err and "Traceback" not in err


@pytest.mark.integration
@needs_model
async def test_chat_with_the_embedded_model_drives_to_the_kitchen_even_behind_a_dead_server() -> None:
    code, out, err = await _run("chat", "--robot", "sim", "--sim-speed", "20",
                                "--llm", f"http://127.0.0.1:{_dead_port()}/v1#edge-model", "--llm", "local",
                                stdin="please drive to the kitchen\n", timeout=600)
    assert code == 0, err
    assert "→ navigate_to(target='kitchen')" in out
    assert "robot> " in out.split("← navigate_to ok", 1)[1]  # it answered in words after the drive


async def test_chat_with_a_robot_at_an_http_address() -> None:
    """`robovoice chat --robot http://127.0.0.1:PORT/mcp`: the robot is a running `robovoice serve`."""
    serve = Child("serve", robovoice("serve", "--robot", "sim://?speed=50", "--transport", "http", "--port", "0",
                                     "--no-audit-log"))
    try:
        url = (await serve.async_wait_for_line("robovoice serve: ready: ", bound=30)).split()[3]
        script: list[ScriptedReply] = [ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),))]
        async with FakeOpenAIServer(script) as server:
            code, out, err = await _run("chat", "--robot", url, "--llm", server.base_url, "--model", server.model,
                                        stdin="switch the projector on\n")
        assert code == 0, err
        assert "→ set_projector_power(on=True)" in out and "← set_projector_power ok" in out
        assert "robot> The projector is now on." in out
    finally:
        assert serve.stop() == 0, serve.output()


async def test_chat_refuses_a_token_in_the_address_and_a_dead_server(tmp_path: Path) -> None:
    code, _, err = await _run("chat", "--robot", "http://127.0.0.1:8765/mcp?token=abc", "--llm", "local")
    assert code == 1 and "no secrets in the URI" in err and "--token-file" in err and "Traceback" not in err
    token = tmp_path / "token"
    token.write_text("s3cret\n")
    code, _, err = await _run("chat", "--robot", f"http://127.0.0.1:{_dead_port()}/mcp", "--token-file", str(token),
                              "--llm", "local")
    assert code == 1 and "cannot reach the robot's MCP server at http://127.0.0.1:" in err
    assert "s3cret" not in err and "Traceback" not in err


async def test_eval_only_names_existing_cases() -> None:
    code, _, err = await _run("eval", str(DATA / "text.jsonl"), "--only", "no-such-case", "--llm", "local")
    assert code == 1 and "--only: no case with id 'no-such-case'" in err
