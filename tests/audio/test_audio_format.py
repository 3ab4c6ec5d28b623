"""Audio values and conversions: exact where they can be, measured where they cannot."""

from __future__ import annotations

import numpy as np
import pytest

from robovoice.audio.format import (
    MODEL_FORMAT,
    AudioChunk,
    AudioFormat,
    FormatConverter,
    Framer,
    Resampler,
    as_float32,
    concat,
    convert,
    float32_to_int16,
    int16_to_float32,
    resample,
    rms_dbfs,
    silence,
    split_chunk,
    to_mono,
)
from robovoice.errors import AudioError


def tone(freq: float, rate: int, seconds: float = 1.0, amp: float = 0.5) -> np.ndarray:
    t = np.arange(int(rate * seconds)) / rate
    return (amp * np.sin(2 * np.pi * freq * t)).astype(np.float32)


def level_db(x: np.ndarray, freq: float, rate: int, amp: float = 0.5) -> float:
    """Level of the `freq` component relative to `amp`, measured on the middle half."""
    mid = x[len(x) // 4 : 3 * len(x) // 4].astype(np.float64)
    t = np.arange(len(mid)) / rate
    c = 2 * abs(np.mean(mid * np.exp(-2j * np.pi * freq * t)))
    return float(20 * np.log10(max(c, 1e-12) / amp))


# --- values ----------------------------------------------------------------------------------


def test_format_validation_and_helpers() -> None:
    fmt = AudioFormat(48000, 2, 2)
    assert fmt.bytes_per_frame == 4
    assert fmt.frames(0.5) == 24000
    assert fmt.seconds(4800) == pytest.approx(0.1)
    assert fmt.with_(rate=16000, channels=1) == AudioFormat(16000, 2, 1)
    assert AudioFormat(16000, 4).dtype == np.float32
    for bad in ((0, 2, 1), (16000, 3, 1), (16000, 2, 0)):
        with pytest.raises(AudioError):
            AudioFormat(*bad)


def test_chunk_checks_dtype_and_shape_and_is_read_only() -> None:
    with pytest.raises(AudioError, match="int16"):
        AudioChunk(np.zeros(10, dtype=np.float32), MODEL_FORMAT)
    with pytest.raises(AudioError, match="shape"):
        AudioChunk(np.zeros((10, 2), dtype=np.int16), MODEL_FORMAT)
    with pytest.raises(AudioError, match="2-channel"):
        AudioChunk(np.zeros(10, dtype=np.int16), AudioFormat(16000, 2, 2))
    source = np.arange(10, dtype=np.int16)
    chunk = AudioChunk(source, MODEL_FORMAT, timestamp=1.5)
    with pytest.raises(ValueError, match="read-only"):
        chunk.samples[0] = 5
    source[0] = 7  # the caller's array itself stays writable
    assert chunk.num_frames == 10
    assert chunk.duration_s == pytest.approx(10 / 16000)
    assert chunk.end_timestamp == pytest.approx(1.5 + 10 / 16000)


def test_bytes_round_trip_mono_stereo_float() -> None:
    stereo = AudioFormat(44100, 2, 2)
    samples = np.array([[1, -1], [32767, -32768], [0, 5]], dtype=np.int16)
    chunk = AudioChunk(samples, stereo)
    assert chunk.bytes == samples.astype("<i2").tobytes()
    back = AudioChunk.from_bytes(chunk.bytes, stereo, 2.0)
    np.testing.assert_array_equal(back.samples, samples)
    assert back.timestamp == 2.0
    f32 = AudioFormat(16000, 4, 1)
    x = np.array([0.5, -0.25, 1.0], dtype=np.float32)
    np.testing.assert_array_equal(AudioChunk.from_bytes(AudioChunk(x, f32).bytes, f32).samples, x)
    with pytest.raises(AudioError, match="whole number"):
        AudioChunk.from_bytes(b"\x00\x01\x02", stereo)


# --- sample types and channels ------------------------------------------------------------------


def test_int16_float32_round_trip_is_exact() -> None:
    every = np.arange(-32768, 32768, dtype=np.int16)
    f = int16_to_float32(every)
    assert f.dtype == np.float32
    assert f.min() == -1.0 and f.max() < 1.0
    np.testing.assert_array_equal(float32_to_int16(f), every)


def test_float_to_int16_rounds_and_clips_without_wrapping() -> None:
    out = float32_to_int16(np.array([0.0, 1.5, -1.5, 1.0, 0.5 / 32768 * 3], dtype=np.float32))
    np.testing.assert_array_equal(out, [0, 32767, -32768, 32767, 2])


def test_to_mono_averages_channels() -> None:
    stereo = np.array([[100, 300], [-32768, -32768], [1, 2]], dtype=np.int16)
    np.testing.assert_array_equal(to_mono(stereo), [200, -32768, 2])
    f = np.array([[0.5, -0.5], [1.0, 0.0]], dtype=np.float32)
    np.testing.assert_allclose(to_mono(f), [0.0, 0.5])
    assert to_mono(np.zeros(4, dtype=np.int16)).shape == (4,)


# --- resampling -----------------------------------------------------------------------------------

RATE_PAIRS = [(48000, 16000), (44100, 16000), (22050, 16000), (8000, 16000), (22050, 48000), (22050, 44100)]


@pytest.mark.parametrize(("src", "dst"), RATE_PAIRS)
def test_resampler_passes_speech_band_and_keeps_length(src: int, dst: int) -> None:
    x = tone(1000, src)
    y = resample(x, src, dst)
    assert len(y) == -(-len(x) * dst // src)
    assert abs(level_db(y, 1000, dst)) < 0.05
    edge = 0.8 * min(src, dst) / 2  # 6.4 kHz when going to 16 kHz
    assert level_db(resample(tone(edge, src), src, dst), edge, dst) > -1.0


@pytest.mark.parametrize(("src", "dst"), [(48000, 16000), (44100, 16000), (22050, 16000)])
def test_downsampling_rejects_aliases(src: int, dst: int) -> None:
    worst = -200.0
    for f in np.linspace(dst / 2 * 1.1, src / 2 * 0.98, 9):
        y = resample(tone(float(f), src), src, dst)
        alias = abs(((f + dst / 2) % dst) - dst / 2)
        worst = max(worst, level_db(y, alias, dst))
    assert worst < -70.0


def test_resampling_keeps_timing() -> None:
    """A click at 0.5 s is still at 0.5 s after resampling (no filter delay)."""
    x = np.zeros(48000, dtype=np.float32)
    x[24000] = 1.0
    y = resample(x, 48000, 16000)
    assert int(np.argmax(np.abs(y))) == 8000


def test_streaming_resampler_equals_one_shot_for_any_chunking() -> None:
    rng = np.random.default_rng(1)
    x = rng.standard_normal(44100).astype(np.float32) * 0.1
    one_shot = resample(x, 44100, 16000)
    r = Resampler(44100, 16000)
    pieces = []
    i = 0
    for size in rng.integers(1, 3000, 200):
        pieces.append(r.process(x[i : i + size]))
        i += int(size)
    pieces.append(r.process(x[i:]))
    assert r.latency_samples > 0  # what the filter holds back until flush
    pieces.append(r.flush())
    np.testing.assert_allclose(np.concatenate(pieces), one_shot, atol=1e-6)
    assert r.latency_samples == 0


def test_resample_int16_and_stereo_keep_dtype_and_channels() -> None:
    x = np.stack([float32_to_int16(tone(440, 22050)), float32_to_int16(tone(880, 22050))], axis=1)
    y = resample(x, 22050, 16000)
    assert y.dtype == np.int16 and y.shape == (16000, 2)
    assert abs(level_db(as_float32(y[:, 1]), 880, 16000)) < 0.1
    assert resample(x, 22050, 22050) is not x


def test_convert_whole_chunk() -> None:
    stereo48 = AudioFormat(48000, 2, 2)
    x = float32_to_int16(np.stack([tone(500, 48000), tone(500, 48000)], axis=1))
    out = convert(AudioChunk(x, stereo48, 3.0), MODEL_FORMAT)
    assert out.format == MODEL_FORMAT and out.num_frames == 16000 and out.timestamp == 3.0
    assert abs(level_db(as_float32(out.samples), 500, 16000)) < 0.05
    up = convert(out, AudioFormat(16000, 4, 2))
    assert up.samples.shape == (16000, 2) and up.samples.dtype == np.float32
    with pytest.raises(AudioError, match="2 channels to 3"):
        convert(AudioChunk(np.zeros((4, 2), np.int16), stereo48), AudioFormat(48000, 2, 3))


def test_format_converter_streams_with_exact_timestamps() -> None:
    fmt = AudioFormat(44100, 2, 2)
    x = float32_to_int16(np.stack([tone(300, 44100, 2.0)] * 2, axis=1))
    conv = FormatConverter(MODEL_FORMAT)
    outs = [conv.convert(c) for c in split_chunk(AudioChunk(x, fmt, 10.0), 1000)]
    tail = conv.flush()
    assert tail is not None
    outs.append(tail)
    total = sum(o.num_frames for o in outs)
    assert total == 32000
    t = 10.0
    for o in outs:
        assert o.timestamp == pytest.approx(t)
        t += o.duration_s
    joined = concat(outs)
    assert abs(level_db(as_float32(joined.samples), 300, 16000)) < 0.05
    with pytest.raises(AudioError, match="changed format"):
        conv.convert(AudioChunk(np.zeros(10, np.int16), MODEL_FORMAT))


def test_format_converter_without_resampling_has_no_tail() -> None:
    conv = FormatConverter(AudioFormat(16000, 4, 1))
    out = conv.convert(AudioChunk(np.array([16384, -16384], np.int16), MODEL_FORMAT))
    np.testing.assert_array_equal(out.samples, [0.5, -0.5])
    assert conv.flush() is None


# --- framing and helpers ---------------------------------------------------------------------------


def test_framer_cuts_exact_frames_across_uneven_chunks() -> None:
    data = np.arange(5000, dtype=np.int16)
    framer = Framer(512)
    frames = []
    offset = 0
    for size in (100, 700, 1, 1500, 2699):
        frames += framer.push(AudioChunk(data[offset : offset + size], MODEL_FORMAT, 2.0 + offset / 16000))
        offset += size
    assert len(frames) == 5000 // 512
    for k, f in enumerate(frames):
        assert f.num_frames == 512
        np.testing.assert_array_equal(f.samples, data[k * 512 : (k + 1) * 512])
        assert f.timestamp == pytest.approx(2.0 + k * 512 / 16000)
    assert framer.pending_samples == 5000 % 512
    framer.reset()
    assert framer.pending_samples == 0
    with pytest.raises(AudioError, match="mono"):
        framer.push(AudioChunk(np.zeros((4, 2), np.int16), AudioFormat(16000, 2, 2)))


def test_concat_silence_rms_and_split() -> None:
    a = silence(MODEL_FORMAT, 0.5, timestamp=1.0)
    b = AudioChunk(np.full(8000, 16384, np.int16), MODEL_FORMAT)
    joined = concat([a, b])
    assert joined.num_frames == 16000 and joined.timestamp == 1.0
    assert rms_dbfs(a.samples) == float("-inf")
    assert rms_dbfs(b.samples) == pytest.approx(-6.02, abs=0.01)
    parts = list(split_chunk(joined, 5000))
    assert [p.num_frames for p in parts] == [5000, 5000, 5000, 1000]
    assert parts[1].timestamp == pytest.approx(1.0 + 5000 / 16000)
    with pytest.raises(AudioError):
        concat([])
    with pytest.raises(AudioError, match="concatenate"):
        concat([a, AudioChunk(np.zeros(3, np.float32), AudioFormat(16000, 4))])
