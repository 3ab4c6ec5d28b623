"""Microphone and speaker over sounddevice (PortAudio), bridged into asyncio.

PortAudio calls our callbacks on its own thread; this module is the one place where
those threads meet the event loop (``loop.call_soon_threadsafe`` in, a lock-protected
queue out). sounddevice is imported only when a device is opened. Tests inject a fake
stream through ``stream_factory`` (headless machines have no devices at all).
"""

from __future__ import annotations

import asyncio
import collections
import importlib
import logging
import threading
from collections.abc import AsyncIterator, Callable
from types import ModuleType
from typing import Any, Protocol

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, PIPER_FORMAT, AudioChunk, AudioFormat, Int16Array, as_int16
from robovoice.errors import AudioError, MissingDependencyError

logger = logging.getLogger(__name__)


class Stream(Protocol):
    """The part of a `sounddevice` stream we use."""

    def start(self) -> None: ...

    def stop(self) -> None: ...

    def close(self) -> None: ...


#: ``factory(fmt, blocksize, callback) -> Stream``; the callback has sounddevice's raw-array
#: signature ``(data, frames, time, status)``.
StreamFactory = Callable[[AudioFormat, int, Callable[..., None]], Stream]


def import_sounddevice(import_module: Callable[[str], ModuleType] = importlib.import_module) -> ModuleType:
    """Import sounddevice, naming the fix when it or PortAudio is missing."""
    try:
        sounddevice = import_module("sounddevice")
    except OSError as exc:  # "PortAudio library not found"
        raise MissingDependencyError(
            "microphone/speaker audio (PortAudio library not found)", "apt-get install libportaudio2"
        ) from exc
    except ImportError as exc:
        raise MissingDependencyError("microphone/speaker audio", "pip install 'robovoice[voice]'") from exc
    return sounddevice


def _device_error(sd: ModuleType, exc: Exception, what: str) -> AudioError:
    try:
        devices = str(sd.query_devices())
    except Exception as query_exc:  # diagnostics only: the original error is what we raise
        devices = f"(cannot list devices: {query_exc})"
    return AudioError(f"cannot open {what}: {exc}. Devices:\n{devices or '(none)'}")


class MicrophoneSource:
    """Captures int16 audio from an input device in chunks of `chunk_frames`.

    Default 16 kHz mono so no resampling is needed (PortAudio/ALSA converts). Chunks that
    the consumer does not take within `max_queued_s` are dropped (logged), never blocking
    the audio thread.
    """

    def __init__(
        self,
        fmt: AudioFormat = MODEL_FORMAT,
        *,
        chunk_frames: int = 1280,
        device: int | str | None = None,
        max_queued_s: float = 2.0,
        stream_factory: StreamFactory | None = None,
    ) -> None:
        if fmt.width != 2:
            raise AudioError("MicrophoneSource captures int16 (width=2)")
        self._format = fmt
        self._chunk_frames = chunk_frames
        self._device = device
        self._max_queued = max(1, round(max_queued_s * fmt.rate / chunk_frames))
        self._factory = stream_factory or self._sounddevice_stream
        self._queue: asyncio.Queue[AudioChunk | None] | None = None
        self._stream: Stream | None = None
        self._frames = 0
        self._t0 = 0.0
        self.dropped_chunks = 0

    @property
    def format(self) -> AudioFormat:
        return self._format

    def _sounddevice_stream(self, fmt: AudioFormat, blocksize: int, callback: Callable[..., None]) -> Stream:
        sd = import_sounddevice()
        try:
            stream: Stream = sd.RawInputStream(
                samplerate=fmt.rate,
                channels=fmt.channels,
                dtype="int16",
                blocksize=blocksize,
                device=self._device,
                callback=callback,
            )
        except sd.PortAudioError as exc:
            raise _device_error(sd, exc, "microphone") from exc
        return stream

    def __aiter__(self) -> AsyncIterator[AudioChunk]:
        return self._chunks()

    async def _chunks(self) -> AsyncIterator[AudioChunk]:
        loop = asyncio.get_running_loop()
        queue: asyncio.Queue[AudioChunk | None] = asyncio.Queue()
        self._queue = queue
        self._t0 = loop.time()
        self._frames = 0

        def on_chunk(chunk: AudioChunk) -> None:
            if queue.qsize() >= self._max_queued:
                self.dropped_chunks += 1
                logger.warning("microphone consumer too slow: dropped a chunk (%d so far)", self.dropped_chunks)
                return
            queue.put_nowait(chunk)

        def callback(data: Any, frames: int, time: Any, status: Any) -> None:  # PortAudio thread
            if status:
                logger.debug("microphone status: %s", status)
            samples = np.frombuffer(bytes(data), dtype="<i2").astype(np.int16)
            if self._format.channels > 1:
                samples = samples.reshape(-1, self._format.channels)
            chunk = AudioChunk(samples, self._format, self._t0 + self._frames / self._format.rate)
            self._frames += frames
            loop.call_soon_threadsafe(on_chunk, chunk)

        self._stream = self._factory(self._format, self._chunk_frames, callback)
        self._stream.start()
        try:
            while True:
                item = await queue.get()
                if item is None:
                    return
                yield item
        finally:
            self._close_stream()

    def _close_stream(self) -> None:
        stream, self._stream = self._stream, None
        if stream is not None:
            stream.stop()
            stream.close()

    async def aclose(self) -> None:
        self._close_stream()
        if self._queue is not None:
            self._queue.put_nowait(None)


class SpeakerSink:
    """Plays chunks on an output device through a queue the audio callback drains.

    `write` applies back-pressure when more than `max_buffer_s` is queued; `stop()` drops
    everything queued at once (barge-in): the device plays silence from its next block.
    Chunks must already be in the sink's format (use `FormatConverter`).
    """

    def __init__(
        self,
        fmt: AudioFormat = PIPER_FORMAT,
        *,
        blocksize: int = 1024,
        device: int | str | None = None,
        max_buffer_s: float = 2.0,
        stream_factory: StreamFactory | None = None,
    ) -> None:
        self.format = fmt
        self._blocksize = blocksize
        self._device = device
        self._max_buffer_frames = round(max_buffer_s * fmt.rate)
        self._factory = stream_factory or self._sounddevice_stream
        self._lock = threading.Lock()
        self._queue: collections.deque[Int16Array] = collections.deque()
        self._queued_frames = 0
        self._stream: Stream | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._space = asyncio.Event()
        self._empty = asyncio.Event()
        self._empty.set()
        self.frames_played = 0

    def _sounddevice_stream(self, fmt: AudioFormat, blocksize: int, callback: Callable[..., None]) -> Stream:
        sd = import_sounddevice()
        try:
            stream: Stream = sd.RawOutputStream(
                samplerate=fmt.rate,
                channels=fmt.channels,
                dtype="int16",
                blocksize=blocksize,
                device=self._device,
                callback=callback,
            )
        except sd.PortAudioError as exc:
            raise _device_error(sd, exc, "speaker") from exc
        return stream

    def _ensure_stream(self) -> None:
        if self._stream is None:
            self._loop = asyncio.get_running_loop()
            self._stream = self._factory(self.format, self._blocksize, self._callback)
            self._stream.start()

    def _callback(self, outdata: Any, frames: int, time: Any, status: Any) -> None:  # PortAudio thread
        if status:
            logger.debug("speaker status: %s", status)
        ch = self.format.channels
        out = np.zeros(frames * ch, dtype=np.int16)
        filled = 0
        with self._lock:
            while filled < out.shape[0] and self._queue:
                head = self._queue[0]
                take = min(head.shape[0], out.shape[0] - filled)
                out[filled : filled + take] = head[:take]
                filled += take
                if take == head.shape[0]:
                    self._queue.popleft()
                else:
                    self._queue[0] = head[take:]
            self._queued_frames -= filled // ch
            self.frames_played += filled // ch
            now_empty = not self._queue
        outdata[:] = out.tobytes()
        if self._loop is not None and filled:
            self._loop.call_soon_threadsafe(self._after_play, now_empty)

    def _after_play(self, now_empty: bool) -> None:
        with self._lock:
            queued = self._queued_frames
            empty = not self._queue
        if queued < self._max_buffer_frames:
            self._space.set()
        if empty and now_empty:
            self._empty.set()

    @property
    def queued_s(self) -> float:
        with self._lock:
            return self._queued_frames / self.format.rate

    async def write(self, chunk: AudioChunk) -> None:
        if chunk.format.rate != self.format.rate or chunk.format.channels != self.format.channels:
            raise AudioError(f"speaker is {self.format}, got {chunk.format}; convert the chunk first")
        self._ensure_stream()
        while True:
            with self._lock:
                if self._queued_frames < self._max_buffer_frames:
                    self._queue.append(np.ascontiguousarray(as_int16(chunk.samples)).reshape(-1))
                    self._queued_frames += chunk.num_frames
                    self._empty.clear()
                    return
                self._space.clear()
            await self._space.wait()

    async def drain(self) -> None:
        """Wait until everything queued has been handed to the device."""
        await self._empty.wait()

    def stop(self) -> None:
        with self._lock:
            dropped = self._queued_frames
            self._queue.clear()
            self._queued_frames = 0
        self._space.set()
        self._empty.set()
        if dropped:
            logger.debug("speaker stop: dropped %.2f s of queued audio", dropped / self.format.rate)

    async def aclose(self) -> None:
        self.stop()
        stream, self._stream = self._stream, None
        if stream is not None:
            stream.stop()
            stream.close()
