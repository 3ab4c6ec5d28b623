"""robovoice against real OpenAI-compatible servers (issue 16), started as docs/llm.md says, each
serving the embedded Qwen2.5-Coder-1.5B GGUF: llama-cpp-python's own server (``python -m
llama_cpp.server``) in its ``chatml-function-calling`` mode and with the GGUF's own chat template
(no ``--chat_format``: tools rendered by the model's Jinja template, calls come back as text), and
llama.cpp's C++ ``llama-server --jinja`` (built by scripts/build_llama_server.sh). Each server is
started once per session on a port the OS chooses, and warmed with the assistant's own prompt as
a deployment would be. `robovoice chat` and `robovoice assist --input`
run as real processes; what reached the sim robot is read from the tool results they print, and
no tool-call syntax may ever be printed or spoken."""

from __future__ import annotations

import asyncio
import os
import re
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import httpx
import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.prompt import SYSTEM_PROMPT
from robovoice.config import RobotConfig
from robovoice.llm.base import ChatMessage
from robovoice.llm.llama_server import MODEL_ALIAS, MODES, running_server
from robovoice.llm.openai_compat import OpenAICompatBackend

pytestmark = [pytest.mark.integration, pytest.mark.slow, pytest.mark.timeout(900)]

ROBOVOICE = [sys.executable, "-m", "robovoice.cli"]
AUDIO = Path(__file__).resolve().parent.parent / "data" / "audio"
SYNTAX = ("functions.", "<tool_call>", "</tool_call>", '"arguments"', "<|im_start|>")
# A CPU server shared with other jobs: a generous first-token deadline (the default for a server on
# this machine is 60 s, `DEADLINES_BY_KIND["local-cpu"]`).
CONFIG = """[[llm.backends]]
url = "{url}"
model = "{model}"
kind = "local-cpu"
first_token_s = 240
"""


@dataclass
class RealServer:
    mode: str
    url: str
    config: Path
    log: Path


async def _warm_up(url: str) -> None:
    """One request with the assistant's system prompt and the sim robot's tools: the server caches
    that prefix, so test turns (like a deployment's) skip reading it again."""
    async with connect_robot(RobotConfig(address="sim://")) as link:
        tools = await link.tools.specs()
    backend = OpenAICompatBackend(url, MODEL_ALIAS)
    try:
        body = backend.request_body([ChatMessage("system", SYSTEM_PROMPT), ChatMessage("user", "Hello!")], tools)
    finally:
        await backend.aclose()
    body.update(stream=False, max_tokens=8)
    body.pop("stream_options", None)
    async with httpx.AsyncClient(timeout=httpx.Timeout(600.0)) as client:
        reply = await client.post(f"{url}/chat/completions", json=body)
    assert reply.status_code == 200, reply.text


@pytest.fixture(scope="session", params=list(MODES))
def real_server(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Iterator[RealServer]:
    """One server per mode per session (the 1.1 GB model loads once), stopped after its tests."""
    mode: str = request.param
    folder = tmp_path_factory.mktemp(f"server-{mode}")
    log = folder / "server.log"
    with running_server(mode, log_path=log) as url:
        models = httpx.get(f"{url}/models", timeout=10.0).json()
        assert [m["id"] for m in models["data"]] == [MODEL_ALIAS]
        asyncio.run(_warm_up(url))
        config = folder / "robovoice.toml"
        config.write_text(CONFIG.format(url=url, model=MODEL_ALIAS))
        yield RealServer(mode, url, config, log)


async def _robovoice(*args: str, stdin: str = "", timeout: float = 600.0) -> tuple[int, str, str]:
    proc = await asyncio.create_subprocess_exec(
        *ROBOVOICE, *args, stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE,
        stderr=asyncio.subprocess.PIPE, env={**os.environ, "PYTHONUNBUFFERED": "1"})
    try:
        out, err = await asyncio.wait_for(proc.communicate(stdin.encode()), timeout)
    finally:
        if proc.returncode is None:
            proc.kill()
            await proc.wait()
    return proc.returncode or 0, out.decode(), err.decode()


@dataclass(frozen=True)
class Run:
    code: int
    out: str
    err: str

    def check(self) -> str:
        """The output of a run that ended cleanly, printed no tool-call syntax and got answers."""
        assert self.code == 0 and "Traceback" not in self.err, self.err[-3000:]
        _assert_no_syntax(self.out)
        assert "can't reach my language model" not in self.out, self.out + self.err[-3000:]
        return self.out


async def _chat(server: RealServer, stdin: str, *options: str) -> Run:
    return Run(*await _robovoice("chat", "--robot", "sim", "--sim-speed", "50", "--config", str(server.config),
                                 *options, stdin=stdin))


def _assert_no_syntax(out: str) -> None:
    said = [line for line in out.splitlines() if line.startswith("robot") or "robot (" in line or "robot:" in line]
    leaked = [line for line in said if any(token in line for token in SYNTAX)]
    assert not leaked, f"tool-call syntax printed as the robot's words: {leaked}"
    assert "functions." not in out and "<tool_call>" not in out


def _robot_lines(out: str) -> list[str]:
    return [line.removeprefix("robot> ") for line in out.splitlines() if line.startswith("robot> ")]


# Failures seen on these servers and who they are reported to (non-strict: each still runs, and
# turns XPASS once fixed). None now: the GGUF template's battery question (docs/llm.md "Recipes")
# passes since a guessed figure is looked up (27 Nov 2026).
KNOWN: dict[tuple[str, str], str] = {}


def _known(request: pytest.FixtureRequest, mode: str, what: str) -> None:
    if (mode, what) in KNOWN:
        request.applymarker(pytest.mark.xfail(reason=KNOWN[mode, what], strict=False))


@pytest.fixture(scope="session")
def drive_chat(real_server: RealServer) -> tuple[str, Run]:
    """One `robovoice chat` drive per server, read by two tests. --max-steps 2: a call, then a
    step without tools, which must end in words (chatml-function-calling went on calling tools
    after the drive when tools were still offered)."""
    return real_server.mode, asyncio.run(_chat(real_server, "please drive to the kitchen\n", "--max-steps", "2"))


async def test_chat_drive_reaches_the_robot(drive_chat: tuple[str, Run], request: pytest.FixtureRequest) -> None:
    mode, run = drive_chat
    _known(request, mode, "calls")
    out = run.check()
    assert "→ navigate_to(target='kitchen')" in out and '"arrived": "kitchen"' in out, out


async def test_chat_drive_ends_in_words(drive_chat: tuple[str, Run], request: pytest.FixtureRequest) -> None:
    mode, run = drive_chat
    _known(request, mode, "calls")
    _known(request, mode, "words")
    out = run.check()
    assert "→ navigate_to(" in out and [line for line in _robot_lines(out) if line.strip()], out


async def test_chat_question(real_server: RealServer, request: pytest.FixtureRequest) -> None:
    _known(request, real_server.mode, "question")
    run = await _chat(real_server, "how much battery do you have?\n", "--max-steps", "2")
    out = run.check()
    assert "→ get_battery_state()" in out and "← get_battery_state ok" in out, out
    # it says the level: the sim's battery is full, and CI once heard "I have a fully charged battery."
    assert re.search(r"robot> .*(\d|percent|full)", out), out + run.err[-3000:]


# The two servers whose calls come back most differently (llama-cpp-python's grammar, llama.cpp's
# own parser): a second call after a tool result. The GGUF template's call after a result is the
# drive's second step (a minute of CI each; the drive and the question run on all three).
@pytest.mark.parametrize("real_server", ["chatml-function-calling", "llama-server"], indirect=True)
async def test_chat_two_step_request(real_server: RealServer, request: pytest.FixtureRequest) -> None:
    _known(request, real_server.mode, "calls")
    out = (await _chat(real_server, "switch on the projector and then drive to the kitchen\n")).check()
    assert "→ set_projector_power(on=True)" in out and "← set_projector_power ok" in out, out
    assert "→ navigate_to(target='kitchen')" in out and '"arrived": "kitchen"' in out, out


# The voice pipeline is the same code whatever the server: on llama.cpp's own C++ server.
@pytest.mark.parametrize("real_server", ["llama-server"], indirect=True)
async def test_assist_voice_turn(real_server: RealServer, tmp_path: Path, request: pytest.FixtureRequest) -> None:
    _known(request, real_server.mode, "calls")
    code, out, err = await _robovoice("assist", "--robot", "sim", "--sim-speed", "50", "--config",
                                      str(real_server.config), "--input", str(AUDIO / "wake_piper_kitchen_pink20.wav"),
                                      "--output-dir", str(tmp_path))
    assert code == 0, err[-3000:]
    assert "Traceback" not in err, err[-3000:]
    _assert_no_syntax(out)
    assert '→ navigate_to(target="kitchen")' in out and "← navigate_to: " in out, out + err[-2000:]
    assert list(tmp_path.glob("turn-*.wav")), "the answer was spoken"
