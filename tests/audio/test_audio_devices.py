"""Microphone and speaker logic over fake PortAudio streams (headless machines have no
devices); the real sounddevice import is checked for its error messages."""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from robovoice.audio.devices import MicrophoneSource, SpeakerSink, import_sounddevice
from robovoice.audio.format import MODEL_FORMAT, PIPER_FORMAT, AudioChunk, AudioFormat
from robovoice.audio.streams import AudioSink, AudioSource
from robovoice.errors import AudioError, MissingDependencyError

from ..installed import missing


class FakeInputStream:
    """Calls the callback from its own thread with consecutive blocks, like PortAudio."""

    def __init__(self, blocks: list[np.ndarray], callback: Callable[..., None]) -> None:
        self._blocks = blocks
        self._callback = callback
        self._thread = threading.Thread(target=self._run)
        self.stopped = threading.Event()
        self.closed = False

    def _run(self) -> None:
        for block in self._blocks:
            if self.stopped.is_set():
                return
            self._callback(block.tobytes(), block.shape[0], None, None)

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self.stopped.set()
        self._thread.join(timeout=5)

    def close(self) -> None:
        self.closed = True


class FakeOutputStream:
    """The test pulls audio out of it, as the device callback would."""

    def __init__(self, callback: Callable[..., None]) -> None:
        self._callback = callback
        self.started = False
        self.closed = False

    def pull(self, frames: int) -> np.ndarray:
        out = bytearray(frames * 2)
        self._callback(memoryview(out), frames, None, None)
        return np.frombuffer(bytes(out), dtype="<i2").astype(np.int16)

    def start(self) -> None:
        self.started = True

    def stop(self) -> None:
        return None

    def close(self) -> None:
        self.closed = True


async def test_microphone_delivers_chunks_in_order_with_timestamps() -> None:
    blocks = [np.full(1280, i, dtype=np.int16) for i in range(6)]
    made: list[FakeInputStream] = []

    def factory(fmt: AudioFormat, blocksize: int, callback: Callable[..., None]) -> FakeInputStream:
        assert fmt == MODEL_FORMAT and blocksize == 1280
        made.append(FakeInputStream(blocks, callback))
        return made[-1]

    mic = MicrophoneSource(stream_factory=factory)
    assert isinstance(mic, AudioSource)
    got: list[AudioChunk] = []

    async def consume() -> None:
        async for chunk in mic:
            got.append(chunk)
            if len(got) == 6:
                await mic.aclose()

    await asyncio.wait_for(consume(), timeout=10)
    assert [int(c.samples[0]) for c in got] == list(range(6))
    assert [c.timestamp - got[0].timestamp for c in got] == pytest.approx([i * 0.08 for i in range(6)])
    assert made[0].stopped.is_set() and made[0].closed


async def test_microphone_drops_chunks_when_the_consumer_falls_behind() -> None:
    blocks = [np.full(160, i, dtype=np.int16) for i in range(50)]
    holder: dict[str, FakeInputStream] = {}

    def factory(fmt: AudioFormat, blocksize: int, callback: Callable[..., None]) -> FakeInputStream:
        holder["s"] = FakeInputStream(blocks, callback)
        return holder["s"]

    mic = MicrophoneSource(chunk_frames=160, max_queued_s=0.05, stream_factory=factory)  # 5 chunks
    it = aiter(mic)
    first = await asyncio.wait_for(anext(it), timeout=10)
    holder["s"]._thread.join(timeout=10)  # the fake device has delivered everything
    for _ in range(3):
        await asyncio.sleep(0)  # let the loop run the queued hand-overs (no wall-clock wait)
    assert mic.dropped_chunks > 0
    await mic.aclose()
    rest = [c async for c in it]
    assert int(first.samples[0]) == 0
    assert 1 + len(rest) + mic.dropped_chunks == 50


def make_speaker(**kwargs: Any) -> tuple[SpeakerSink, dict[str, FakeOutputStream]]:
    holder: dict[str, FakeOutputStream] = {}

    def factory(fmt: AudioFormat, blocksize: int, callback: Callable[..., None]) -> FakeOutputStream:
        holder["s"] = FakeOutputStream(callback)
        return holder["s"]

    return SpeakerSink(PIPER_FORMAT, stream_factory=factory, **kwargs), holder


async def test_speaker_plays_queued_audio_in_order_then_silence() -> None:
    sink, holder = make_speaker()
    assert isinstance(sink, AudioSink)
    await sink.write(AudioChunk(np.arange(1, 301, dtype=np.int16), PIPER_FORMAT))
    await sink.write(AudioChunk(np.arange(301, 401, dtype=np.int16), PIPER_FORMAT))
    stream = holder["s"]
    assert stream.started
    assert sink.queued_s == pytest.approx(400 / 22050)
    a = stream.pull(256)
    b = stream.pull(256)
    np.testing.assert_array_equal(np.concatenate([a, b])[:400], np.arange(1, 401))
    assert not b[144:].any()
    await asyncio.wait_for(sink.drain(), timeout=5)
    assert sink.frames_played == 400
    await sink.aclose()
    assert stream.closed


async def test_speaker_stop_drops_queued_audio_at_once() -> None:
    sink, holder = make_speaker()
    await sink.write(AudioChunk(np.ones(22050, dtype=np.int16), PIPER_FORMAT))
    assert holder["s"].pull(512).all()
    sink.stop()
    assert sink.queued_s == 0
    assert not holder["s"].pull(512).any()
    await asyncio.wait_for(sink.drain(), timeout=5)


async def test_speaker_write_waits_while_the_buffer_is_full() -> None:
    sink, holder = make_speaker(max_buffer_s=0.05)  # ~1100 frames
    await sink.write(AudioChunk(np.ones(2000, dtype=np.int16), PIPER_FORMAT))
    pending = asyncio.ensure_future(sink.write(AudioChunk(np.ones(100, dtype=np.int16), PIPER_FORMAT)))
    await asyncio.sleep(0)
    assert not pending.done()
    holder["s"].pull(1500)
    await asyncio.wait_for(pending, timeout=5)
    assert sink.queued_s == pytest.approx(600 / 22050)
    await sink.aclose()


async def test_speaker_refuses_other_formats() -> None:
    sink, _ = make_speaker()
    with pytest.raises(AudioError, match="convert"):
        await sink.write(AudioChunk(np.zeros(10, np.int16), MODEL_FORMAT))


def test_missing_portaudio_names_the_debian_package() -> None:
    def no_portaudio(name: str) -> Any:
        raise OSError("PortAudio library not found")

    with pytest.raises(MissingDependencyError, match="apt-get install libportaudio2"):
        import_sounddevice(no_portaudio)


def test_missing_sounddevice_names_the_extra() -> None:
    def not_installed(name: str) -> Any:
        raise ModuleNotFoundError("No module named 'sounddevice'")

    with pytest.raises(MissingDependencyError, match=r"robovoice\[voice\]"):
        import_sounddevice(not_installed)


def test_opening_a_real_device_without_one_is_an_audio_error() -> None:
    """Headless CI: PortAudio is installed but there is no device; the error lists devices."""
    try:
        sd = import_sounddevice()
    except MissingDependencyError:
        missing("PortAudio", "Debian package libportaudio2")
    if len(sd.query_devices()) > 0:
        pytest.skip("this machine has audio devices")  # about the machine, not a missing install
    mic = MicrophoneSource()

    async def open_it() -> None:
        async for _ in mic:
            break

    with pytest.raises(AudioError, match="cannot open microphone"):
        asyncio.run(open_it())
