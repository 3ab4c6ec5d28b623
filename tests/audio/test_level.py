"""The speech-to-noise estimate of a VAD utterance (audio/level.py): the words against the
noise in the pre- and post-roll around them."""

from __future__ import annotations

import numpy as np
import pytest

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat, float32_to_int16
from robovoice.audio.level import CLEAN_DB, speech_to_noise_db

RATE = MODEL_FORMAT.rate


def level(x: np.ndarray, dbfs: float) -> np.ndarray:
    scaled: np.ndarray = x * 10 ** (dbfs / 20) / np.sqrt(np.mean(x * x))
    return scaled


def utterance(speech_db: float, noise_db: float | None, pre_s: float = 0.3, speech_s: float = 1.5,
              post_s: float = 0.2, seed: int = 1) -> AudioChunk:
    """Noise all through; speech-like bursts (4 Hz syllables, as `babble` in the voice kit)
    between a pre-roll and a post-roll, as `Endpointer` cuts an utterance."""
    rng = np.random.default_rng(seed)
    n_pre, n_speech, n_post = (round(s * RATE) for s in (pre_s, speech_s, post_s))
    t = np.arange(n_speech) / RATE
    words = level(rng.standard_normal(n_speech) * (0.2 + np.abs(np.sin(2 * np.pi * 4 * t))), speech_db)
    x = np.concatenate([np.zeros(n_pre), words, np.zeros(n_post)])
    if noise_db is not None:
        x += level(rng.standard_normal(x.size), noise_db)
    return AudioChunk(float32_to_int16(x.astype(np.float32)), MODEL_FORMAT)


@pytest.mark.parametrize(("speech_db", "noise_db"), [(-20, -40), (-20, -32), (-20, -24), (-20, -20), (-26, -23)])
def test_the_estimate_follows_the_mixing_ratio(speech_db: float, noise_db: float) -> None:
    mixed = speech_db - noise_db
    estimate = speech_to_noise_db(utterance(speech_db, noise_db))
    assert estimate is not None
    # the louder half of the words' frames: a little above the mean ratio, never below it by much
    assert mixed - 1.0 < estimate < mixed + 4.0, (mixed, estimate)


def test_louder_noise_gives_a_lower_estimate() -> None:
    estimates = [speech_to_noise_db(utterance(-20, noise)) for noise in (-40, -30, -24, -18)]
    assert all(e is not None for e in estimates)
    assert estimates == sorted(estimates, reverse=True)  # type: ignore[type-var]


def test_digital_silence_around_the_words_is_clean() -> None:
    assert speech_to_noise_db(utterance(-20, None)) == CLEAN_DB


def test_an_edge_holding_speech_does_not_count_as_noise() -> None:
    """No pre-roll (a stream that began mid-word): the quiet post-roll is the noise."""
    with_roll = speech_to_noise_db(utterance(-20, -32))
    without = speech_to_noise_db(utterance(-20, -32, pre_s=0.0))
    assert with_roll is not None and without is not None
    assert abs(with_roll - without) < 2.0
    assert speech_to_noise_db(utterance(-20, None, pre_s=0.0)) == CLEAN_DB


def test_too_short_to_tell_is_none() -> None:
    assert speech_to_noise_db(utterance(-20, -30, pre_s=0.2, speech_s=0.05, post_s=0.15)) is None


def test_float_and_stereo_audio_read_the_same_as_int16() -> None:
    chunk = utterance(-20, -30)
    as_float = chunk.samples.astype(np.float32) / 32768.0
    float_chunk = AudioChunk(as_float, AudioFormat(RATE, width=4))
    stereo = AudioChunk(np.stack([chunk.samples, chunk.samples], axis=1), AudioFormat(RATE, channels=2))
    expected = speech_to_noise_db(chunk)
    assert expected is not None
    assert speech_to_noise_db(float_chunk) == pytest.approx(expected, abs=0.01)
    assert speech_to_noise_db(stereo) == pytest.approx(expected, abs=0.01)
