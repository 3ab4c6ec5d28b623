"""The audio evaluation set (tests/data/eval/audio.jsonl, DESIGN.md §6) and running audio
cases through the voice pipeline the way `robovoice eval` does."""

from __future__ import annotations

import wave
from pathlib import Path

import numpy as np
import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.audio.format import as_int16
from robovoice.audio.wav import read_wav
from robovoice.config import RobotConfig
from robovoice.eval.cases import load_cases
from robovoice.eval.runner import run_eval
from robovoice.llm.fake_server import CallbackReply, FakeOpenAIServer
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.evaluation import open_clip_runner
from robovoice.voice.models import VoiceModels
from robovoice.voice.recording import reply_latency

from .voice_kit import DATA, keyword_router

CASES = DATA / "eval" / "audio.jsonl"


def test_the_audio_set_is_complete() -> None:
    cases = load_cases(CASES)
    assert len(cases) >= 40
    assert all(c.audio is not None and c.text is None for c in cases)
    assert sum(1 for c in cases if c.wake) >= 20 and sum(1 for c in cases if c.wake is False) >= 15
    notes = " ".join(str(getattr(c, "note", "")) for c in cases)
    for voice in ("piper", "espeak:"):
        assert voice in notes
    for noise in ("clean", "20 dB", "10 dB"):
        assert noise in notes
    total = 0
    for case in cases:
        assert case.audio is not None
        with wave.open(str(case.audio)) as wf:
            assert (wf.getnchannels(), wf.getsampwidth(), wf.getframerate()) == (1, 2, 16000), case.id
            seconds = wf.getnframes() / wf.getframerate()
        assert 1.5 < seconds < 7.0, case.id  # a two-step request runs to about 6.5 s
        total += Path(case.audio).stat().st_size
    assert total < 9_000_000


@pytest.mark.integration
@pytest.mark.timeout(300)
async def test_audio_cases_through_the_pipeline(voice_models: VoiceModels, tmp_path: Path) -> None:
    wanted = ["wake-projector-on-1", "nowake-02", "wake-stop-2", "nowake-stop-2"]
    cases = [c for c in load_cases(CASES) if c.id in wanted]
    async with FakeOpenAIServer(default=CallbackReply(keyword_router)) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            async with open_clip_runner(models=voice_models, record_dir=tmp_path) as audio:  # eval --record
                robot = RobotConfig(address="sim://?speed=2")
                report = await run_eval(cases, backend, lambda: connect_robot(robot), audio=audio)
        finally:
            await backend.aclose()
    summary = report.to_dict()
    by_id = {r["id"]: r for r in summary["results"]}
    assert all(r["passed"] for r in summary["results"]), [(r["id"], r["reason"]) for r in summary["results"]]
    assert by_id["nowake-02"]["calls"] == [] and by_id["nowake-02"]["wake_words"] == 0
    assert by_id["wake-stop-2"]["calls"] == [{"tool": "stop_robot", "args": {}, "error": None, "resolved": {}}]
    assert by_id["wake-stop-2"]["stops"] == 1
    assert by_id["nowake-stop-2"]["stops"] == 1
    # the stops never asked the model, and the projector's result was answered by its success
    # phrase: one request in all
    assert [r.last_user_text for r in server.requests] == ["turn on the projector."]
    assert "first_audio" in summary["stages"] and "transcript" in summary["stages"]
    # one session recording per case, channel 1 the clip itself from its first sample
    assert sorted(p.stem for p in tmp_path.glob("*.wav")) == sorted(wanted)
    for case in cases:
        assert case.audio is not None
        session, clip_audio = read_wav(tmp_path / f"{case.id}.wav"), read_wav(case.audio)
        assert session.format.channels == 2
        said = as_int16(clip_audio.samples).astype(np.int32)
        both = as_int16(session.samples).astype(np.int32)
        sounded = np.flatnonzero(both[:, 1])  # until the robot makes a sound, the microphone hears the clip alone
        quiet = min(len(said), int(sounded[0]) if sounded.size else len(said))
        assert quiet > 8000 and np.abs(both[:quiet, 0] - said[:quiet]).max() <= 1, case.id
    answered = read_wav(tmp_path / "wake-projector-on-1.wav")
    latency = reply_latency(answered, robot_dbfs=-100)
    assert latency is not None and 0.0 < latency < 30.0
    assert reply_latency(read_wav(tmp_path / "nowake-02.wav")) is None  # the robot said nothing
