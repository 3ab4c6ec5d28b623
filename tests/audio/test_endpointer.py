"""Endpointer state machine with made-up probabilities; SpeechSegmenter with a model-free VAD.

Frames are 512 samples (32 ms); every sample of frame k holds the value k, so the audio of
an utterance shows exactly which frames it kept.
"""

from __future__ import annotations

import numpy as np
import pytest

from robovoice.audio.fakes import EnergyVAD
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat, float32_to_int16
from robovoice.audio.vad import (
    Endpointer,
    EndpointerConfig,
    SpeechEnded,
    SpeechSegmenter,
    SpeechStarted,
    VADEvent,
    VADModel,
)
from robovoice.errors import AudioError, ConfigError

F = 0.032  # frame duration


def feed(ep: Endpointer, probs: list[float], first: int = 0) -> list[tuple[int, VADEvent]]:
    """Feed frames first, first+1, ...; return (frame index, event) pairs."""
    out = []
    for k, p in enumerate(probs, start=first):
        frame = np.full(512, k, dtype=np.int16)
        out += [(k, e) for e in ep.update(p, frame, k * F)]
    return out


def frames_in(ended: SpeechEnded) -> list[int]:
    return [int(v) for v in ended.audio.samples[::512]]


def test_utterance_boundaries_pre_roll_and_post_roll() -> None:
    events = feed(Endpointer(), [0.1] * 20 + [0.9] * 30 + [0.1] * 20)
    assert [type(e) for _, e in events] == [SpeechStarted, SpeechEnded]
    (k_start, started), (k_end, ended) = events
    assert isinstance(started, SpeechStarted) and isinstance(ended, SpeechEnded)
    assert k_start == 24  # confirmed after min_speech_s (5 frames = 0.16 s >= 0.15 s)
    assert started.timestamp == pytest.approx(20 * F)  # but dated at the onset
    assert k_end == 65  # 16 silent frames = 0.512 s >= 0.5 s end-of-turn silence
    assert ended.start == pytest.approx(20 * F)
    assert ended.end == pytest.approx(50 * F)
    assert ended.speech_duration_s == pytest.approx(30 * F)
    assert not ended.truncated
    kept = frames_in(ended)
    assert kept[0] == 11  # 9 frames (0.288 s) of pre-roll before the onset
    assert kept[-1] == 56  # 0.2 s of post-roll after the last speech frame
    assert kept == list(range(11, 57))
    assert ended.audio.timestamp == pytest.approx(11 * F)
    assert ended.audio.format == MODEL_FORMAT


def test_end_of_turn_silence_is_configurable() -> None:
    ep = Endpointer(EndpointerConfig(end_silence_s=0.7))
    events = feed(ep, [0.9] * 10 + [0.0] * 30)
    assert [k for k, e in events if isinstance(e, SpeechEnded)] == [10 + 22 - 1]  # 22 frames = 0.704 s


def test_hysteresis_start_needs_start_threshold_continuing_needs_stop_threshold() -> None:
    assert feed(Endpointer(), [0.45] * 50) == []  # never reaches 0.5
    events = feed(Endpointer(), [0.1] * 5 + [0.6] * 6 + [0.4] * 20 + [0.3] * 16)
    ended = [e for _, e in events if isinstance(e, SpeechEnded)]
    assert len(ended) == 1
    assert ended[0].end == pytest.approx(31 * F)  # 0.4 >= stop threshold keeps speech going; 0.3 does not


def test_short_pauses_inside_a_sentence_do_not_end_it() -> None:
    probs = [0.9] * 20 + [0.1] * 12 + [0.9] * 20 + [0.1] * 15 + [0.9] * 10 + [0.1] * 16
    events = feed(Endpointer(), probs)
    ended = [e for _, e in events if isinstance(e, SpeechEnded)]
    assert len(ended) == 1
    assert ended[0].start == 0.0
    assert ended[0].end == pytest.approx(77 * F)


def test_clicks_shorter_than_min_speech_are_ignored_but_kept_as_pre_roll() -> None:
    ep = Endpointer()
    assert feed(ep, [0.0] * 10 + [0.9] * 3 + [0.0] * 16) == []
    assert not ep.in_speech
    events = feed(ep, [0.0] * 4 + [0.9] * 10 + [0.0] * 16, first=29)
    ended = [e for _, e in events if isinstance(e, SpeechEnded)]
    assert len(ended) == 1
    assert ended[0].start == pytest.approx(33 * F)
    assert frames_in(ended[0])[0] == 24  # 9 frames of pre-roll, whatever they were


def test_max_utterance_length_truncates_and_speech_continues_in_a_new_utterance() -> None:
    ep = Endpointer(EndpointerConfig(max_utterance_s=1.0))
    events = feed(ep, [0.9] * 50 + [0.0] * 16)
    kinds = [(k, type(e).__name__) for k, e in events]
    assert kinds == [(4, "SpeechStarted"), (31, "SpeechEnded"), (36, "SpeechStarted"), (65, "SpeechEnded")]
    first = events[1][1]
    assert isinstance(first, SpeechEnded) and first.truncated
    assert first.end == pytest.approx(32 * F)
    last = events[3][1]
    assert isinstance(last, SpeechEnded) and not last.truncated


def test_flush_ends_speech_in_progress_and_drops_a_pending_onset() -> None:
    ep = Endpointer()
    feed(ep, [0.0] * 3 + [0.9] * 10)
    assert ep.in_speech
    (ended,) = ep.flush()
    assert isinstance(ended, SpeechEnded) and ended.end == pytest.approx(13 * F)
    assert not ep.in_speech
    feed(ep, [0.9] * 2, first=20)
    assert ep.flush() == []
    assert ep.flush() == []


def test_reset_forgets_everything() -> None:
    ep = Endpointer()
    feed(ep, [0.9] * 10)
    ep.reset()
    assert not ep.in_speech
    assert ep.flush() == []


@pytest.mark.parametrize(
    "kwargs",
    [
        {"start_threshold": 0.3, "stop_threshold": 0.5},
        {"pre_roll_s": -0.1},
        {"end_silence_s": -1.0},
        {"max_utterance_s": 0.1},
    ],
)
def test_bad_config_is_refused(kwargs: dict[str, float]) -> None:
    with pytest.raises(ConfigError):
        EndpointerConfig(**kwargs)


def test_segmenter_with_energy_vad_finds_a_tone_burst() -> None:
    rate = 16000
    t = np.arange(rate) / rate
    burst = float32_to_int16(0.3 * np.sin(2 * np.pi * 300 * t))
    audio = np.concatenate([np.zeros(rate // 2, np.int16), burst, np.zeros(rate, np.int16)])
    vad = EnergyVAD()
    assert isinstance(vad, VADModel)
    seg = SpeechSegmenter(vad)
    events: list[VADEvent] = []
    for i in range(0, len(audio), 1000):
        events += seg.feed(AudioChunk(audio[i : i + 1000], MODEL_FORMAT, i / rate))
    events += seg.flush()
    ended = [e for e in events if isinstance(e, SpeechEnded)]
    assert len(ended) == 1
    assert ended[0].start == pytest.approx(0.5, abs=F)
    assert ended[0].end == pytest.approx(1.5, abs=F)
    assert seg.last_probability < 0.01


def test_segmenter_flush_closes_an_utterance_when_the_stream_ends_mid_speech() -> None:
    seg = SpeechSegmenter(EnergyVAD())
    loud = np.full(16000, 8000, dtype=np.int16)
    assert [type(e) for e in seg.feed(AudioChunk(loud, MODEL_FORMAT))] == [SpeechStarted]
    (ended,) = seg.flush()
    assert isinstance(ended, SpeechEnded)
    assert ended.end == pytest.approx(31 * F)  # the 31 whole frames of the 1 s chunk


def test_segmenter_refuses_audio_that_is_not_16k_mono() -> None:
    with pytest.raises(AudioError, match="16 kHz mono"):
        SpeechSegmenter(EnergyVAD()).feed(AudioChunk(np.zeros(10, np.int16), AudioFormat(8000)))
