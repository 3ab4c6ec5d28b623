"""Benchmark helpers with fakes (the real-model runs are `bench.run_all`)."""

from __future__ import annotations

import numpy as np
import pytest

from robovoice.audio.bench import (
    LabelledAudio,
    Stats,
    frontend_cpu,
    normalize_text,
    stt_latency,
    tts_first_audio,
    wake_false_accepts,
    word_error_rate,
)
from robovoice.audio.fakes import EnergyVAD, ScriptedTranscriber, ScriptedWakeDetector, ToneSynthesizer
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat
from robovoice.audio.wake import WakeDeciderConfig
from robovoice.errors import AudioError


def test_normalize_text() -> None:
    assert normalize_text("Robot, go to the KITCHEN!") == "robot go to the kitchen"
    assert normalize_text("The weather to-day: it's fine.") == "the weather today it's fine"
    assert normalize_text("  'Quoted'  words\u2019 ") == "quoted words"


@pytest.mark.parametrize(
    ("ref", "hyp", "wer"),
    [
        ("go to the kitchen", "Go to the kitchen.", 0.0),
        ("go to the kitchen", "go to kitchen", 0.25),
        ("go to the kitchen", "go to the big kitchen", 0.25),
        ("go to the kitchen", "go into the chicken", 0.5),
        ("call anna", "", 1.0),
        ("", "", 0.0),
        ("", "noise", 1.0),
    ],
)
def test_word_error_rate(ref: str, hyp: str, wer: float) -> None:
    assert word_error_rate(ref, hyp) == pytest.approx(wer)


def test_stats() -> None:
    s = Stats.of([1.0, 2.0, 3.0, 4.0, 100.0])
    assert (s.median, s.max, s.n) == (3.0, 100.0, 5)
    assert s.mean == pytest.approx(22.0)
    assert 4.0 < s.p95 < 100.0
    with pytest.raises(AudioError):
        Stats.of([])


def test_frontend_cpu_reports_per_block_and_per_frame_costs() -> None:
    audio = AudioChunk(np.zeros(16000 * 11, np.int16), MODEL_FORMAT)
    r = frontend_cpu(audio, ScriptedWakeDetector(), EnergyVAD(), block_s=5.0)
    assert r.block_s == pytest.approx(4.96)  # 62 chunks of 80 ms
    assert r.core_percent.n == 2
    assert r.wake_ms_per_80ms.n == r.vad_ms_per_80ms.n == 124
    assert r.core_percent.median > 0
    with pytest.raises(AudioError, match="at least"):
        frontend_cpu(AudioChunk(np.zeros(1000, np.int16), MODEL_FORMAT), ScriptedWakeDetector(), EnergyVAD())


def test_false_accepts_counts_detections_per_hour() -> None:
    scores = [0.0] * 100 + [0.9] + [0.0] * 100 + [0.8, 0.9] + [0.0] * 200
    audio = AudioChunk(np.zeros(1280 * 450, np.int16), AudioFormat(16000))
    r = wake_false_accepts(audio, ScriptedWakeDetector(scores), WakeDeciderConfig(threshold=0.5))
    assert r.accepts == 2
    assert r.timestamps_s == pytest.approx((101 * 0.08, 202 * 0.08))
    assert r.per_hour == pytest.approx(2 / (450 * 0.08 / 3600))
    assert r.max_score == 0.9


def test_stt_latency_scores_each_clip_once_and_times_every_call() -> None:
    clip = AudioChunk(np.zeros(16000, np.int16), MODEL_FORMAT)
    clips = [LabelledAudio("a", clip, "go to the kitchen"), LabelledAudio("b", clip, "call anna")]
    fake = ScriptedTranscriber(["go to the kitchen", "x", "call hannah", "y"])
    r = stt_latency("fake", fake, clips, repeats=2)
    assert [x.hypothesis for x in r.results] == ["go to the kitchen", "call hannah"]
    assert r.wer == pytest.approx(1 / 6)
    assert r.latency_s.n == 4 and r.real_time_factor.n == 4


def test_tts_first_audio() -> None:
    r = tts_first_audio(ToneSynthesizer(), ["Hello there.", "Okay."], repeats=2)
    assert r.first_audio_s.n == 4
    assert r.first_audio_s.median <= r.total_s.median
    with pytest.raises(AudioError, match="no audio"):
        tts_first_audio(ToneSynthesizer(), [" "], repeats=1)
