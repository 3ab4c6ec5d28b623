"""WAV files as audio sources and sinks, and an in-memory sink: the fakes of the I/O seams.

Files are read with `soundfile` (libsndfile, in the ``robovoice[voice]`` extra): integer PCM
WAV of any width, float WAV, A-law, and whatever else libsndfile reads, all delivered as int16.
They are written as 16-bit PCM WAV with the standard library's `wave`.
"""

from __future__ import annotations

import asyncio
import logging
import wave
from collections.abc import AsyncIterator, Awaitable, Callable, Iterator
from pathlib import Path
from types import TracebackType

import numpy as np

from robovoice.audio.format import AudioChunk, AudioFormat, Int16Array, as_int16, concat, float32_to_int16
from robovoice.errors import AudioError, MissingDependencyError

logger = logging.getLogger(__name__)

_INSTALL = "pip install 'robovoice[voice]'"


# --- reading ----------------------------------------------------------------------------

# Integer PCM is read as int16 by libsndfile itself (8-bit unsigned centred, 24/32-bit shifted
# down); everything else (float, A-law, ...) as float32, converted here: libsndfile does not
# scale float data read as integers.
_INTEGER_PCM = frozenset({"PCM_U8", "PCM_S8", "PCM_16", "PCM_24", "PCM_32"})


def _iter_wav(path: Path, frames_per_read: int) -> tuple[AudioFormat, int, Iterator[Int16Array]]:
    """(format as int16, total frames, iterator of int16 blocks) for any file libsndfile reads."""
    try:
        import soundfile as sf
    except (ImportError, OSError) as exc:  # OSError: the libsndfile library is missing
        raise MissingDependencyError(f"reading the audio file {path}", _INSTALL) from exc
    try:
        info = sf.info(str(path))
    except RuntimeError as exc:  # soundfile.LibsndfileError derives from RuntimeError
        what = "open" if not path.exists() else "read"
        raise AudioError(f"cannot {what} audio file {path}: {exc}") from exc
    fmt = AudioFormat(rate=int(info.samplerate), width=2, channels=int(info.channels))
    as_int = info.subtype in _INTEGER_PCM

    def blocks() -> Iterator[Int16Array]:
        for block in sf.blocks(str(path), blocksize=frames_per_read, dtype="int16" if as_int else "float32",
                               always_2d=False):
            yield block if as_int else float32_to_int16(block)

    return fmt, int(info.frames), blocks()


def read_wav(path: str | Path) -> AudioChunk:
    """A whole WAV file as one int16 chunk in the file's rate and channel count."""
    fmt, _, blocks = _iter_wav(Path(path), 1 << 16)
    parts = list(blocks)
    if not parts:
        shape: tuple[int, ...] = (0,) if fmt.channels == 1 else (0, fmt.channels)
        return AudioChunk(np.zeros(shape, dtype=np.int16), fmt)
    return AudioChunk(np.concatenate(parts), fmt)


def write_wav(path: str | Path, chunk: AudioChunk) -> None:
    """Write a chunk as 16-bit PCM WAV (float samples are converted)."""
    with WavWriter(Path(path), chunk.format) as w:
        w.write(chunk)


class WavWriter:
    """Synchronous 16-bit PCM WAV writer for one format."""

    def __init__(self, path: Path, fmt: AudioFormat) -> None:
        self.format = fmt
        try:
            self._wf = wave.open(str(path), "wb")  # noqa: SIM115 (closed in close())
        except OSError as exc:
            raise AudioError(f"cannot create WAV file {path}: {exc}") from exc
        self._wf.setnchannels(fmt.channels)
        self._wf.setsampwidth(2)
        self._wf.setframerate(fmt.rate)

    def write(self, chunk: AudioChunk) -> None:
        if (chunk.format.rate, chunk.format.channels) != (self.format.rate, self.format.channels):
            raise AudioError(f"WAV file is {self.format}, got a chunk in {chunk.format}; convert it first")
        self._wf.writeframes(np.ascontiguousarray(as_int16(chunk.samples), dtype="<i2").tobytes())

    def close(self) -> None:
        self._wf.close()

    def __enter__(self) -> WavWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


# --- source ------------------------------------------------------------------------------


class WavSource:
    """Yields a WAV file as int16 chunks of `chunk_frames` frames (the last may be shorter).

    Timestamps start at `start_timestamp` and follow the sample count. By default chunks
    come as fast as they are consumed; ``realtime=True`` paces them like a microphone (each
    chunk is released when its last sample "has been spoken"), using the event loop's clock
    and `asyncio.sleep` unless `clock`/`sleep` are given (tests inject fakes).
    """

    def __init__(
        self,
        path: str | Path,
        *,
        chunk_frames: int = 1024,
        realtime: bool = False,
        start_timestamp: float = 0.0,
        clock: Callable[[], float] | None = None,
        sleep: Callable[[float], Awaitable[None]] | None = None,
    ) -> None:
        if chunk_frames <= 0:
            raise AudioError(f"chunk_frames must be positive, got {chunk_frames}")
        self.path = Path(path)
        self._chunk_frames = chunk_frames
        self._realtime = realtime
        self._t0 = start_timestamp
        self._clock = clock
        self._sleep = sleep or asyncio.sleep
        self._format, self._total, self._blocks = _iter_wav(self.path, chunk_frames)
        self._closed = False
        self._iterated = False

    @property
    def format(self) -> AudioFormat:
        return self._format

    @property
    def duration_s(self) -> float:
        return self._total / self._format.rate

    def __aiter__(self) -> AsyncIterator[AudioChunk]:
        if self._iterated:
            raise AudioError(f"WavSource({self.path}) can be iterated once; create a new one")
        self._iterated = True
        return self._chunks()

    async def _chunks(self) -> AsyncIterator[AudioChunk]:
        clock = self._clock or asyncio.get_running_loop().time
        started = clock()
        frames = 0
        for block in self._blocks:
            if self._closed:
                break
            chunk = AudioChunk(block, self._format, self._t0 + frames / self._format.rate)
            frames += chunk.num_frames
            if self._realtime:
                # a chunk is "captured" once its last sample has been spoken
                delay = started + frames / self._format.rate - clock()
                if delay > 0:
                    await self._sleep(delay)
            yield chunk
            if not self._realtime:
                await asyncio.sleep(0)  # let other tasks run, as a real device would
        logger.debug("WAV source %s ended after %d frames", self.path, frames)

    async def aclose(self) -> None:
        self._closed = True


# --- sinks -------------------------------------------------------------------------------


class WavSink:
    """Writes whatever it is given to a 16-bit WAV file; the format comes from the first
    chunk unless given. Nothing is queued, so `stop()` only counts barge-ins."""

    def __init__(self, path: str | Path, fmt: AudioFormat | None = None) -> None:
        self.path = Path(path)
        self._format = fmt
        self._writer: WavWriter | None = WavWriter(self.path, fmt) if fmt is not None else None
        self.stop_count = 0
        self.frames_written = 0

    async def write(self, chunk: AudioChunk) -> None:
        if self._writer is None:
            self._format = chunk.format
            self._writer = WavWriter(self.path, chunk.format)
        self._writer.write(chunk)
        self.frames_written += chunk.num_frames

    async def drain(self) -> None:
        return None

    def stop(self) -> None:
        self.stop_count += 1

    async def aclose(self) -> None:
        if self._writer is None:  # nothing written: still leave a valid (empty) file
            self._writer = WavWriter(self.path, self._format or AudioFormat(16000))
        self._writer.close()

    async def __aenter__(self) -> WavSink:
        return self

    async def __aexit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        await self.aclose()


class MemorySink:
    """Keeps every chunk written, for tests; `stop()` calls are counted and recorded as the
    number of chunks written before each stop (so a test can see where barge-in cut in)."""

    def __init__(self) -> None:
        self.chunks: list[AudioChunk] = []
        self.stops: list[int] = []
        self.closed = False

    async def write(self, chunk: AudioChunk) -> None:
        if self.closed:
            raise AudioError("write to a closed MemorySink")
        self.chunks.append(chunk)

    async def drain(self) -> None:
        return None

    def stop(self) -> None:
        self.stops.append(len(self.chunks))

    async def aclose(self) -> None:
        self.closed = True

    @property
    def stop_count(self) -> int:
        return len(self.stops)

    def audio(self) -> AudioChunk:
        """Everything written, joined (raises AudioError when nothing was written)."""
        return concat(self.chunks)

    @property
    def duration_s(self) -> float:
        return sum(c.duration_s for c in self.chunks)
