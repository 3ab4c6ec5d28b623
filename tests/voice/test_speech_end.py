"""Latency from the user's last word (issue 12): stream time mapped to the wall clock, and the
turn's stages re-based on the utterance's end beside the end-of-turn decision."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.metrics import TurnMetrics
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, as_int16, silence
from robovoice.audio.vad import SileroVAD, SpeechEnded, SpeechSegmenter
from robovoice.audio.wav import write_wav
from robovoice.config import RobotConfig
from robovoice.eval.cases import Case
from robovoice.eval.runner import run_eval
from robovoice.llm.fake_server import FakeOpenAIServer, TextReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.clock import StreamAnchor
from robovoice.voice.evaluation import open_clip_runner
from robovoice.voice.events import VoiceTurnFinished, VoiceTurnStarted
from robovoice.voice.lastword import last_word_end
from robovoice.voice.models import VoiceModels

from .voice_kit import SettableTranscriber, clip, join, voice_session, wake_command


def test_the_anchor_takes_the_least_delayed_chunk() -> None:
    anchor = StreamAnchor()
    assert anchor.wall_time(1.0) is None
    # 80 ms chunks whose stream time 0 is wall time 100.0, delivered 0-30 ms late
    for i, late in enumerate((0.03, 0.002, 0.02, 0.011, 0.03), start=1):
        anchor.observe(100.0 + 0.08 * i + late, 0.08 * i)
    assert anchor.wall_time(0.25) == pytest.approx(100.252)


def test_the_anchor_follows_the_sources_speed_and_a_change_of_pace() -> None:
    fast = StreamAnchor(speed=4.0)
    fast.observe(10.0 + 2.0 / 4, 2.0)  # 2 stream seconds took half a wall second
    assert fast.wall_time(3.0) == pytest.approx(10.75)
    anchor = StreamAnchor()
    anchor.observe(50.0, 10.0)
    anchor.observe(51.0, 100.0)  # 90 stream seconds in one wall second (an unpaced stretch) ...
    for i in range(1, 80):  # ... then real time, 80 ms chunks, the front end falling 2 s behind
        anchor.observe(51.0 + 0.08 * i + 0.025 * i, 100.0 + 0.08 * i)
    assert anchor.wall_time(106.0) == pytest.approx(57.0), "the present pace, not the backlog"
    unpaced = StreamAnchor(speed=math.inf)
    unpaced.observe(1.0, 30.0)
    assert unpaced.wall_time(30.0) is None, "an unpaced source has no wall time"
    with pytest.raises(ValueError, match="got 0"):
        StreamAnchor(speed=0.0)


def test_stages_from_the_last_word_are_the_decision_marks_shifted() -> None:
    metrics = TurnMetrics(clock=lambda: 20.0, start=20.0)
    metrics.mark("endpoint", 20.004)
    metrics.mark("first_audio", 21.1)
    assert metrics.from_speech_end() == {}, "no last word known: no second view"
    metrics.speech_end = 19.42
    assert metrics.from_speech_end() == {"endpoint": 584.0, "first_audio": 1680.0}
    assert metrics.as_dict()["first_audio"] == pytest.approx(1100.0), "the old origin is kept"


@pytest.mark.timeout(90)
async def test_a_command_turn_knows_when_the_user_stopped_speaking(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend,
) -> None:
    server.push(TextReply("Hello."))
    transcriber.text = "Hey Jarvis, say hello."
    async with voice_session(fakes, backend) as s:
        speech = s.room.say(wake_command(1.0), gap_s=0.3)
        await s.log.wait_for(VoiceTurnStarted)
        done = await s.log.wait_for(VoiceTurnFinished)
        await s.settle()
    assert done.result is not None and done.result.metrics.speech_end is not None
    spoken = done.result.metrics.from_speech_end()
    assert set(done.latency_ms) - {"model_ms", "tools_ms", "stt_ms", "tts_ms"} <= set(spoken)
    # the end of turn is decided after the end-of-turn silence that follows the last voiced
    # frame (0.5 s by default, shorter when the words so far are a complete request)
    assert 150.0 <= spoken["endpoint"] <= 700.0, spoken
    wait = spoken["endpoint"] - done.latency_ms["endpoint"]
    for stage in ("transcript", "first_sentence", "first_audio"):
        assert spoken[stage] == pytest.approx(done.latency_ms[stage] + wait, abs=0.2), stage
    # the room's own record: the robot's first sound, back by the latency, is where the input ended
    t0, played = s.room.played[0]
    first_sound = t0 + float(np.flatnonzero(as_int16(played.samples))[0]) / MODEL_FORMAT.rate
    assert first_sound - spoken["first_audio"] / 1000 == pytest.approx(speech.end, abs=0.04)


@pytest.mark.timeout(90)
async def test_eval_reports_audio_cases_from_the_last_word(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend,
    tmp_path: Path,
) -> None:
    server.push(TextReply("Hello."))
    transcriber.text = "Hey Jarvis, say hello."
    write_wav(tmp_path / "hello.wav", join(wake_command(1.0), silence(MODEL_FORMAT, 0.3)))
    cases = [Case(id="hello", audio=tmp_path / "hello.wav"), Case(id="typed", text="Say hello.")]
    server.push(TextReply("Hello again."))
    async with open_clip_runner(models=fakes) as audio:
        robot = RobotConfig(address="sim://?speed=20")
        report = await run_eval(cases, backend, lambda: connect_robot(robot), audio=audio)
    summary = report.to_dict()
    spoken, typed = summary["results"]
    assert "latency_from_speech_end_ms" not in typed, "a typed case has no last word"
    from_last_word, from_decision = spoken["latency_from_speech_end_ms"], spoken["latency_ms"]
    assert from_last_word["first_audio"] > from_decision["first_audio"] + 150.0
    assert summary["speech_end_to_first_audio"] == {"p50": from_last_word["first_audio"],
                                                    "p95": from_last_word["first_audio"], "n": 1}
    assert summary["stages_from_speech_end"]["first_audio"]["n"] == 1
    assert summary["stages"]["first_sentence"]["n"] == 2, "the old view keeps every case"


def _vad_utterances(audio: AudioChunk) -> list[SpeechEnded]:
    segmenter = SpeechSegmenter(SileroVAD())
    padded = join(audio, silence(MODEL_FORMAT, 1.0))
    ended: list[SpeechEnded] = []
    for i in range(0, padded.num_frames - 1279, 1280):
        chunk = AudioChunk(padded.samples[i : i + 1280], MODEL_FORMAT, i / MODEL_FORMAT.rate)
        ended += [e for e in segmenter.feed(chunk) if isinstance(e, SpeechEnded)]
    return ended


def _audible_end(audio: AudioChunk) -> float:
    return float(np.flatnonzero(np.abs(as_int16(audio.samples)) > 328)[-1]) / MODEL_FORMAT.rate  # -40 dBFS


@pytest.mark.parametrize("name", ["audio/wake_piper_projector", "audio/cmd_piper_kitchen", "eval/wake-places-1"])
def test_the_last_word_ends_where_the_sound_does_not_where_silero_lets_go(name: str) -> None:
    audio = clip(name)
    [utt] = _vad_utterances(audio)
    truth = _audible_end(audio)
    assert utt.end - truth > 0.05, "Silero's last voiced frame ends well after the voice"
    assert abs(last_word_end(utt.audio, utt.end) - truth) <= 0.03


def test_in_noise_the_vads_end_is_kept() -> None:
    audio = clip("audio/wake_piper_kitchen_pink20")
    [utt] = _vad_utterances(audio)
    assert last_word_end(utt.audio, utt.end) == utt.end
    quiet = silence(MODEL_FORMAT, 0.5, timestamp=3.0)
    assert last_word_end(quiet, 3.2) == 3.2, "nothing voiced: the VAD's end"
