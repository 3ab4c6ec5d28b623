"""`robovoice demo` and `robovoice assist --input` as a user runs them (subprocesses), with the
fake vLLM server as the model so the run is quick and deterministic."""

from __future__ import annotations

import asyncio
import sys
import wave
from pathlib import Path

import pytest

from robovoice.llm.fake_server import CallbackReply, FakeOpenAIServer

from .voice_kit import TEST_AUDIO, keyword_router

pytestmark = [pytest.mark.integration, pytest.mark.timeout(600)]


async def _robovoice(*args: str, timeout: float = 500.0) -> tuple[int, str]:
    proc = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "robovoice.cli", *args,
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
    )
    try:
        async with asyncio.timeout(timeout):
            out, _ = await proc.communicate()
    finally:
        if proc.returncode is None:
            proc.kill()
            await proc.wait()
    assert proc.returncode is not None
    return proc.returncode, out.decode()


async def test_demo_runs_the_scripted_conversation(tmp_path: Path) -> None:
    async with FakeOpenAIServer(default=CallbackReply(keyword_router)) as server:
        code, out = await _robovoice("demo", "--output-dir", str(tmp_path), "--llm", f"{server.base_url}#fake-model")
    failed = [block for block in out.split("── ")[1:] if "✘ FAILED" in block]
    assert code == 0, "\n".join(failed) + out[-2000:]
    assert "8/8 steps did the right thing" in out
    for needle in ("→ navigate_to(target=\"kitchen\")", "! STOP (\"Stop the robot!\"): stop_robot, straight",
                   "■ robot stopped", "latency from end of speech: transcript"):
        assert needle in out, needle
    # The remote caller's "Hey Jarvis" never woke the robot. Whether the echo canceller left enough
    # of it for the wake detector to fire (and be rejected as the robot's own playback) depends on
    # how the machine's timing falls, so the test asserts what holds either way.
    remote = out.split("── 4. remote participant ──")[1].split("── 5.")[0]
    assert "✔ ok" in remote and "· wake word (" not in remote and "→ " not in remote, remote
    answers = sorted(tmp_path.glob("turn-*.wav"))
    assert len(answers) >= 6 and (tmp_path / "conversation.wav").is_file()
    with wave.open(str(answers[0])) as wf:
        assert wf.getnframes() > 0 and wf.getframerate() == 22050


async def test_assist_processes_wav_files_in_one_conversation(tmp_path: Path) -> None:
    files = [TEST_AUDIO / "wake_piper_projector.wav", TEST_AUDIO / "cmd_piper_kitchen.wav",
             TEST_AUDIO / "wake_piper_kitchen_pink20.wav"]
    async with FakeOpenAIServer(default=CallbackReply(keyword_router)) as server:
        code, out = await _robovoice("assist", "--robot", "sim", "--sim-speed", "10", "--llm",
                                     f"{server.base_url}#fake-model", "--input", *map(str, files),
                                     "--output-dir", str(tmp_path))
    failed = [block for block in out.split("── ")[1:] if "✘ FAILED" in block]
    assert code == 0, "\n".join(failed) + out[-2000:]
    assert "→ set_projector_power(on=true)" in out and "→ navigate_to(target=\"kitchen\")" in out
    assert "speech ignored: no wake word" in out  # the middle file has no wake word
    assert len(list(tmp_path.glob("turn-*.wav"))) == 2, out[-3000:]  # what made an extra turn, if one was


async def test_assist_rejects_missing_files(tmp_path: Path) -> None:
    code, out = await _robovoice("assist", "--robot", "sim", "--input", str(tmp_path / "nope.wav"))
    assert code == 1 and "no such WAV file" in out


def test_the_transcript_printer_marks_an_unsure_wake_word() -> None:
    import io

    from robovoice.commands.voice import TranscriptPrinter
    from robovoice.voice.events import WakeWordHeard

    out = io.StringIO()
    printer = TranscriptPrinter(out)
    printer(WakeWordHeard(0.97, 1.0))
    printer(WakeWordHeard(0.31, 5.0, sure=False))
    sure, unsure = out.getvalue().splitlines()
    assert sure.endswith("· wake word (0.97)")
    assert unsure.endswith("· wake word (0.31, unsure: it counts if the words name the robot)")
