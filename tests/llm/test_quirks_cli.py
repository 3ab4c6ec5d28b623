"""`robovoice chat` (a real process) against servers with real servers' quirks: the calls reach
the sim robot, the answers are printed, and no tool-call syntax is ever shown as the robot's words."""

from __future__ import annotations

import asyncio
import os
import re
import sys

from robovoice.llm.fake_server import FakeOpenAIServer, Quirks, ScriptedCall, ScriptedReply, TextReply, ToolCallReply

ROBOVOICE = [sys.executable, "-m", "robovoice.cli"]


async def chat(server: FakeOpenAIServer, stdin: str, timeout: float = 240) -> tuple[int, str, str]:
    proc = await asyncio.create_subprocess_exec(
        *ROBOVOICE, "chat", "--robot", "sim", "--sim-speed", "50", "--llm", server.base_url, "--model", server.model,
        stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
        env={**os.environ, "PYTHONUNBUFFERED": "1"})
    out, err = await asyncio.wait_for(proc.communicate(stdin.encode()), timeout)
    return proc.returncode or 0, out.decode(), err.decode()


def robot_lines(out: str) -> list[str]:
    return [line for line in out.splitlines() if line.startswith("robot> ")]


async def test_chat_against_llama_cpp_python_chatml_function_calling_quirks() -> None:
    """The issue-16 session, as llama-cpp-python 0.3.36 answered it (seen with curl): a streamed
    tool call is an event stream of pings that then closes; a plain reply is constrained by the
    call grammar, so its content is ``functions.get_battery_state:``; no usage."""
    quirks = Quirks(no_streamed_tool_calls=True, keep_alives=True, no_usage=True)
    script: list[ScriptedReply] = [
        ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),)),  # answered by its success phrase
        TextReply("functions.get_battery_state:"),
        TextReply("My battery is at 80 percent."),
    ]
    async with FakeOpenAIServer(script, quirks=quirks) as server:
        code, out, err = await chat(server, "please drive to the kitchen\nhow much battery do you have?\n")
    assert code == 0, err
    assert "→ navigate_to(target='kitchen')" in out and '"arrived": "kitchen"' in out
    assert "→ get_battery_state()" in out and "← get_battery_state ok" in out
    # the figure is the battery's own (the drive drains it: 80 or 81 % by the machine's speed)
    arrived, battery = robot_lines(out)
    assert arrived == "robot> I am in the kitchen now."
    assert re.fullmatch(r"robot> My battery is at 8\d percent\.", battery), battery
    assert "functions." not in out and "Traceback" not in err
    assert [r.body["stream"] for r in server.requests] == [True, False, False, False]


async def test_chat_against_a_hermes_server_that_writes_calls_as_tool_call_tags() -> None:
    """Qwen2.5 behind a server with no tool parser: ``<tool_call>`` text after a sentence,
    plus fields this client does not know and a busy first answer (503, Retry-After)."""
    quirks = Quirks(tool_calls_as="hermes", unknown_fields=True, busy_status=503, busy_retry_after="0.2")
    script: list[ScriptedReply] = [
        ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),), text="On my way to the kitchen."),
    ]
    async with FakeOpenAIServer(script, quirks=quirks) as server:
        code, out, err = await chat(server, "please drive to the kitchen\n")
    assert code == 0, err
    assert "→ navigate_to(target='kitchen')" in out and '"arrived": "kitchen"' in out
    assert robot_lines(out) == ["robot> On my way to the kitchen.", "robot> I am in the kitchen now."]
    assert "tool_call" not in out and '"name"' not in out and "Traceback" not in err
    assert server.busy_sent == 1 and len(server.requests) == 2  # the busy answer, then one model step


async def test_chat_never_prints_control_tokens_a_server_lets_through() -> None:
    """A server that does not strip the chat template's end marker: the sentence is shown, the
    marker never (the speech guard at the chat printer)."""
    async with FakeOpenAIServer([TextReply("Hello there.<|im_end|>")]) as server:
        code, out, err = await chat(server, "hello\n")
    assert code == 0, err
    assert robot_lines(out) == ["robot> Hello there."] and "<|" not in out
