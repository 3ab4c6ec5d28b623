"""`robovoice console` as a user runs it: a child process, its page found from its ready line,
`POST /api/say` answered with the turn and its navigate_to call; SIGTERM ends it with 0."""

from __future__ import annotations

import asyncio
import signal
import sys

import httpx
import pytest

from robovoice.cli import main
from robovoice.llm.fake_server import FakeOpenAIServer

from .console_testkit import BOUND_S
from .test_console_api import GO_TO_KITCHEN


async def test_the_command_serves_the_page_and_api_say_drives_the_robot() -> None:
    async with FakeOpenAIServer(GO_TO_KITCHEN) as server:
        process = await asyncio.create_subprocess_exec(
            sys.executable, "-m", "robovoice.cli", "console", "--robot", "sim://?speed=50", "--port", "0",
            "--no-voice", "--llm", server.base_url, "--model", server.model,
            stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE)
        try:
            assert process.stderr is not None
            async with asyncio.timeout(BOUND_S):
                line = (await process.stderr.readline()).decode()
            assert line.startswith("robovoice console: http://127.0.0.1:"), line
            url = line.split()[2]
            async with httpx.AsyncClient(base_url=url, timeout=BOUND_S) as http:
                assert "robovoice console" in (await http.get("/")).text
                turn = (await http.post("/api/say", json={"text": "please go to the kitchen"})).json()
            assert turn["calls"] == [{"name": "navigate_to", "arguments": {"target": "kitchen"}}]
            process.send_signal(signal.SIGTERM)
            async with asyncio.timeout(BOUND_S):
                assert await process.wait() == 0
        finally:
            if process.returncode is None:
                process.kill()
                await process.wait()


def test_a_non_loopback_host_without_a_token_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["console", "--host", "0.0.0.0", "--no-voice"]) == 1
    assert "without a bearer token" in capsys.readouterr().err
