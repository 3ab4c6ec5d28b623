"""`robovoice bench voice stops` (voice/bench_stops.py) with fake models: stop clips said while
the sim robot drives are timed from the last word to the stop call and its answer, and the
robot halts each time."""

from __future__ import annotations

from pathlib import Path

import pytest

from robovoice.audio.wav import write_wav
from robovoice.voice.bench_stops import bench_stops

from .voice_kit import SettableTranscriber, babble, fake_models

pytestmark = pytest.mark.timeout(120)


async def test_each_stop_is_timed_from_the_last_word_and_halts_the_drive(tmp_path: Path) -> None:
    clip = tmp_path / "stop.wav"
    write_wav(clip, babble(0.8))  # speech-like noise for the energy VAD; the fake hears "Stop!"
    stt = SettableTranscriber()
    stt.by_length = lambda seconds: "Stop!" if seconds > 0.5 else ""  # the robot's short reply is no stop
    result = await bench_stops(2, models=fake_models(stt), wavs=[clip])
    assert result["stops"] == 2 and result["stopped"] == 2, result
    assert result["missed"] == []
    figures = result["from_last_word_ms"]
    for stop in result["per_stop"]:
        assert stop["clip"] == "stop.wav" and stop["ok"]
        # the stop is decided at the first pause after the word (the fake transcribes at once),
        # not after the end-of-turn silence; the call after it, its answer after the call
        assert 0 <= stop["decided"] < 250 and stop["decided"] <= stop["stop_sent"] <= stop["stop_answered"], stop
    assert figures["stop_answered"]["n"] == 2 and figures["stop_sent"]["p50"] <= figures["stop_answered"]["p50"]


async def test_a_clip_that_is_no_stop_is_reported_as_missed(tmp_path: Path) -> None:
    clip = tmp_path / "chatter.wav"
    write_wav(clip, babble(0.8))
    result = await bench_stops(1, models=fake_models(SettableTranscriber("Nice weather.")), wavs=[clip])
    assert result["stopped"] == 0 and result["missed"] == ["chatter.wav"]
    assert {"reason": "not_a_stop", "text": "Nice weather."} in result["ignored"]
    assert result["from_last_word_ms"]["stop_answered"] is None
