"""WAV sources and sinks, the in-memory sink."""

from __future__ import annotations

import wave
from pathlib import Path

import numpy as np
import pytest

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat, float32_to_int16
from robovoice.audio.streams import AudioSink, AudioSource, converted
from robovoice.audio.wav import MemorySink, WavSink, WavSource, read_wav, write_wav
from robovoice.errors import AudioError


def ramp(n: int, channels: int = 1) -> np.ndarray:
    x = (np.arange(n * channels, dtype=np.int64) * 7 % 65536 - 32768).astype(np.int16)
    return x.reshape(-1, channels) if channels > 1 else x


def test_write_and_read_round_trip(tmp_path: Path) -> None:
    fmt = AudioFormat(44100, 2, 2)
    chunk = AudioChunk(ramp(1000, 2), fmt)
    write_wav(tmp_path / "a.wav", chunk)
    back = read_wav(tmp_path / "a.wav")
    assert back.format == fmt
    np.testing.assert_array_equal(back.samples, chunk.samples)


def test_float_chunks_are_written_as_int16(tmp_path: Path) -> None:
    f32 = AudioFormat(16000, 4, 1)
    write_wav(tmp_path / "f.wav", AudioChunk(np.array([0.5, -0.5, 0.0], np.float32), f32))
    back = read_wav(tmp_path / "f.wav")
    assert back.format == MODEL_FORMAT
    np.testing.assert_array_equal(back.samples, [16384, -16384, 0])


def test_reads_24_bit_and_8_bit_pcm(tmp_path: Path) -> None:
    values = np.array([0, 1 << 22, -(1 << 23), (1 << 23) - 1], dtype=np.int32)
    raw24 = b"".join(int(v).to_bytes(3, "little", signed=True) for v in values)
    with wave.open(str(tmp_path / "p24.wav"), "wb") as wf:
        wf.setnchannels(1)
        wf.setsampwidth(3)
        wf.setframerate(8000)
        wf.writeframes(raw24)
    np.testing.assert_array_equal(read_wav(tmp_path / "p24.wav").samples, [0, 16384, -32768, 32767])
    with wave.open(str(tmp_path / "p8.wav"), "wb") as wf:
        wf.setnchannels(1)
        wf.setsampwidth(1)
        wf.setframerate(8000)
        wf.writeframes(bytes([128, 0, 255]))
    np.testing.assert_array_equal(read_wav(tmp_path / "p8.wav").samples, [0, -32768, 32512])


def test_reads_float_wav_through_soundfile(tmp_path: Path) -> None:
    import soundfile as sf

    x = np.array([0.25, -0.5, 0.0, 0.999], dtype=np.float32)
    sf.write(str(tmp_path / "float.wav"), x, 22050, subtype="FLOAT")
    chunk = read_wav(tmp_path / "float.wav")
    assert chunk.format == AudioFormat(22050, 2, 1)
    np.testing.assert_array_equal(chunk.samples, float32_to_int16(x).clip(-32768, 32767))


def test_reads_32_bit_pcm_and_a_law_stereo(tmp_path: Path) -> None:
    import soundfile as sf

    values = np.array([0, 1 << 30, -(1 << 31), (1 << 31) - 1], dtype=np.int32)
    sf.write(str(tmp_path / "p32.wav"), values, 8000, subtype="PCM_32")
    np.testing.assert_array_equal(read_wav(tmp_path / "p32.wav").samples, [0, 16384, -32768, 32767])
    stereo = np.array([[0.0, 0.5], [-0.5, 0.25]], dtype=np.float32)
    sf.write(str(tmp_path / "alaw.wav"), stereo, 8000, subtype="ALAW")
    chunk = read_wav(tmp_path / "alaw.wav")
    assert chunk.format == AudioFormat(8000, 2, 2) and chunk.samples.shape == (2, 2)
    np.testing.assert_allclose(chunk.samples / 32768, stereo, atol=0.02)  # A-law is lossy


def test_missing_or_bad_file_raises_audio_error(tmp_path: Path) -> None:
    with pytest.raises(AudioError, match="cannot open"):
        read_wav(tmp_path / "missing.wav")
    (tmp_path / "junk.wav").write_bytes(b"not a wav at all")
    with pytest.raises(AudioError):
        read_wav(tmp_path / "junk.wav")


async def test_wav_source_yields_fixed_chunks_with_timestamps(tmp_path: Path) -> None:
    data = ramp(5000)
    write_wav(tmp_path / "s.wav", AudioChunk(data, MODEL_FORMAT))
    source = WavSource(tmp_path / "s.wav", chunk_frames=1024, start_timestamp=5.0)
    assert isinstance(source, AudioSource)
    assert source.format == MODEL_FORMAT
    assert source.duration_s == pytest.approx(5000 / 16000)
    chunks = [c async for c in source]
    assert [c.num_frames for c in chunks] == [1024, 1024, 1024, 1024, 904]
    assert [c.timestamp for c in chunks] == pytest.approx([5.0 + i * 1024 / 16000 for i in range(5)])
    np.testing.assert_array_equal(np.concatenate([c.samples for c in chunks]), data)
    with pytest.raises(AudioError, match="once"):
        source.__aiter__()


async def test_wav_source_stops_after_aclose(tmp_path: Path) -> None:
    write_wav(tmp_path / "s.wav", AudioChunk(ramp(10000), MODEL_FORMAT))
    source = WavSource(tmp_path / "s.wav", chunk_frames=1000)
    got = []
    async for chunk in source:
        got.append(chunk)
        if len(got) == 2:
            await source.aclose()
    assert len(got) == 2


async def test_converted_stream_from_44k_stereo_file(tmp_path: Path) -> None:
    t = np.arange(44100) / 44100
    x = float32_to_int16(0.3 * np.sin(2 * np.pi * 440 * t)).astype(np.int16)
    write_wav(tmp_path / "st.wav", AudioChunk(np.stack([x, x], axis=1), AudioFormat(44100, 2, 2)))
    out = [c async for c in converted(aiter(WavSource(tmp_path / "st.wav", chunk_frames=777)), MODEL_FORMAT)]
    assert all(c.format == MODEL_FORMAT for c in out)
    assert sum(c.num_frames for c in out) == 16000
    assert out[-1].timestamp == pytest.approx(sum(c.num_frames for c in out[:-1]) / 16000)


async def test_wav_sink_writes_everything(tmp_path: Path) -> None:
    sink = WavSink(tmp_path / "out.wav")
    assert isinstance(sink, AudioSink)
    async with sink:
        await sink.write(AudioChunk(ramp(100), MODEL_FORMAT))
        await sink.write(AudioChunk(ramp(50), MODEL_FORMAT))
        sink.stop()
        await sink.drain()
    assert sink.stop_count == 1 and sink.frames_written == 150
    back = read_wav(tmp_path / "out.wav")
    np.testing.assert_array_equal(back.samples, np.concatenate([ramp(100), ramp(50)]))
    with pytest.raises(AudioError, match="convert it first"):
        w = WavSink(tmp_path / "o2.wav", MODEL_FORMAT)
        await w.write(AudioChunk(ramp(10), AudioFormat(22050)))


async def test_wav_sink_without_writes_leaves_a_valid_empty_file(tmp_path: Path) -> None:
    sink = WavSink(tmp_path / "empty.wav")
    await sink.aclose()
    assert read_wav(tmp_path / "empty.wav").num_frames == 0


async def test_memory_sink_records_chunks_and_stops() -> None:
    sink = MemorySink()
    assert isinstance(sink, AudioSink)
    await sink.write(AudioChunk(ramp(10), MODEL_FORMAT))
    sink.stop()
    await sink.write(AudioChunk(ramp(20), MODEL_FORMAT))
    assert sink.stops == [1] and sink.stop_count == 1
    assert sink.audio().num_frames == 30
    assert sink.duration_s == pytest.approx(30 / 16000)
    await sink.aclose()
    with pytest.raises(AudioError, match="closed"):
        await sink.write(AudioChunk(ramp(1), MODEL_FORMAT))


async def test_wav_source_realtime_pacing_follows_the_clock(tmp_path: Path) -> None:
    """Each chunk is released when its last sample would have been spoken (fake clock)."""
    write_wav(tmp_path / "s.wav", AudioChunk(ramp(4000), MODEL_FORMAT))
    now = [100.0]
    waits: list[float] = []

    async def fake_sleep(seconds: float) -> None:
        waits.append(seconds)
        now[0] += seconds

    source = WavSource(tmp_path / "s.wav", chunk_frames=1600, realtime=True, clock=lambda: now[0], sleep=fake_sleep)
    released = []
    async for chunk in source:
        released.append((now[0], chunk.end_timestamp))
        now[0] += 0.01  # the consumer takes 10 ms per chunk
    assert [round(t - 100.0, 4) for t, _ in released] == [0.1, 0.2, 0.25]
    assert all(abs((t - 100.0) - end) < 1e-9 for t, end in released)
    assert waits == pytest.approx([0.1, 0.09, 0.04])
