"""Self-describing audio values and every conversion between formats (DESIGN.md §4.4).

`AudioFormat` says what the numbers in an `AudioChunk` mean; everything that changes
format -- sample type (int16 <-> float32), channel count (stereo -> mono) and sample
rate (any rate -> 16 kHz for wake word/VAD/STT, 22.05 kHz TTS -> output device rate)
-- lives in this one module.

Resampling is libsoxr (`soxr`, in the ``robovoice[voice]`` extra), one-shot or streaming so
a microphone at 48 kHz can be converted chunk by chunk without seams; its "HQ" recipe passes
the speech band flat and rejects aliases by far more than the 70 dB tests/audio asks for.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Final, TypeAlias

import numpy as np
import numpy.typing as npt
import soxr

from robovoice.errors import AudioError

Int16Array: TypeAlias = npt.NDArray[np.int16]
Float32Array: TypeAlias = npt.NDArray[np.float32]
Samples: TypeAlias = npt.NDArray[Any]

_DTYPES: Final[dict[int, type[np.generic]]] = {2: np.int16, 4: np.float32}


@dataclass(frozen=True, slots=True)
class AudioFormat:
    """Sample rate (Hz), sample width in bytes and channel count.

    ``width=2`` is signed 16-bit PCM (`numpy.int16`); ``width=4`` is 32-bit float in
    [-1, 1] (`numpy.float32`). Multi-channel samples are interleaved frames.
    """

    rate: int
    width: int = 2
    channels: int = 1

    def __post_init__(self) -> None:
        if self.rate <= 0:
            raise AudioError(f"sample rate must be positive, got {self.rate}")
        if self.width not in _DTYPES:
            raise AudioError(f"sample width must be 2 (int16) or 4 (float32) bytes, got {self.width}")
        if self.channels < 1:
            raise AudioError(f"channel count must be >= 1, got {self.channels}")

    @property
    def dtype(self) -> np.dtype[Any]:
        return np.dtype(_DTYPES[self.width])

    @property
    def bytes_per_frame(self) -> int:
        return self.width * self.channels

    def frames(self, seconds: float) -> int:
        """Number of sample frames in `seconds` (rounded to nearest)."""
        return round(seconds * self.rate)

    def seconds(self, frames: int) -> float:
        return frames / self.rate

    def with_(self, *, rate: int | None = None, width: int | None = None, channels: int | None = None) -> AudioFormat:
        return AudioFormat(
            rate=self.rate if rate is None else rate,
            width=self.width if width is None else width,
            channels=self.channels if channels is None else channels,
        )


#: What wake word, VAD and STT models take: 16 kHz mono int16.
MODEL_FORMAT: Final = AudioFormat(rate=16000, width=2, channels=1)
#: What the Piper voice produces: 22.05 kHz mono int16.
PIPER_FORMAT: Final = AudioFormat(rate=22050, width=2, channels=1)


@dataclass(frozen=True, slots=True, eq=False)
class AudioChunk:
    """A piece of audio that knows its own format and where it sits in its stream.

    `samples` has shape ``(frames,)`` for mono or ``(frames, channels)`` otherwise, with the
    dtype of `format` (int16 or float32); it is made read-only. `timestamp` is the stream
    time in seconds of the first sample (a WAV file starts at 0.0).
    """

    samples: Samples
    format: AudioFormat
    timestamp: float = 0.0

    def __post_init__(self) -> None:
        arr = np.asarray(self.samples)
        if arr.dtype != self.format.dtype:
            raise AudioError(f"samples are {arr.dtype}, format {self.format} needs {self.format.dtype}")
        if self.format.channels == 1:
            if arr.ndim == 2 and arr.shape[1] == 1:
                arr = arr[:, 0]
            if arr.ndim != 1:
                raise AudioError(f"mono samples must have shape (frames,), got {arr.shape}")
        elif arr.ndim != 2 or arr.shape[1] != self.format.channels:
            raise AudioError(
                f"{self.format.channels}-channel samples must have shape (frames, {self.format.channels}), "
                f"got {arr.shape}"
            )
        view = arr.view()
        view.flags.writeable = False
        object.__setattr__(self, "samples", view)

    @classmethod
    def from_bytes(cls, data: bytes, fmt: AudioFormat, timestamp: float = 0.0) -> AudioChunk:
        """Interleaved little-endian PCM (int16) or float32 bytes -> chunk."""
        if len(data) % fmt.bytes_per_frame:
            raise AudioError(f"{len(data)} bytes is not a whole number of {fmt.bytes_per_frame}-byte frames")
        arr = np.frombuffer(data, dtype=fmt.dtype.newbyteorder("<")).astype(fmt.dtype)
        if fmt.channels > 1:
            arr = arr.reshape(-1, fmt.channels)
        return cls(arr, fmt, timestamp)

    @property
    def bytes(self) -> bytes:
        """Interleaved little-endian bytes (what WAV files and sound cards use)."""
        return np.ascontiguousarray(self.samples, dtype=self.format.dtype.newbyteorder("<")).tobytes()

    @property
    def num_frames(self) -> int:
        return int(self.samples.shape[0])

    @property
    def duration_s(self) -> float:
        return self.num_frames / self.format.rate

    @property
    def end_timestamp(self) -> float:
        return self.timestamp + self.duration_s

    def __repr__(self) -> str:
        return (
            f"AudioChunk({self.num_frames} frames, {self.format.rate} Hz, width {self.format.width}, "
            f"{self.format.channels} ch, t={self.timestamp:.3f}s)"
        )


# --- sample type and channels ---------------------------------------------------------


def int16_to_float32(samples: Samples) -> Float32Array:
    """int16 PCM -> float32 in [-1, 1) (divides by 32768, so the round trip is exact)."""
    return (np.asarray(samples, dtype=np.int16).astype(np.float32)) / np.float32(32768.0)


def float32_to_int16(samples: Samples) -> Int16Array:
    """float in [-1, 1] -> int16 PCM, rounded and clipped (no wrap-around on overload)."""
    scaled = np.rint(np.asarray(samples, dtype=np.float32) * np.float32(32768.0))
    out: Int16Array = np.clip(scaled, -32768, 32767).astype(np.int16)
    return out


def as_float32(samples: Samples) -> Float32Array:
    """Any supported sample array (int16 or float) -> float32 in [-1, 1]."""
    arr = np.asarray(samples)
    if arr.dtype == np.int16:
        return int16_to_float32(arr)
    if arr.dtype.kind == "f":
        return arr.astype(np.float32, copy=False)
    raise AudioError(f"unsupported sample dtype {arr.dtype}")


def as_int16(samples: Samples) -> Int16Array:
    """Any supported sample array (int16 or float) -> int16 PCM."""
    arr = np.asarray(samples)
    if arr.dtype == np.int16:
        return arr
    if arr.dtype.kind == "f":
        return float32_to_int16(arr)
    raise AudioError(f"unsupported sample dtype {arr.dtype}")


def to_mono(samples: Samples) -> Samples:
    """(frames, channels) -> (frames,) by averaging the channels; mono passes through."""
    arr = np.asarray(samples)
    if arr.ndim == 1:
        return arr
    if arr.ndim != 2:
        raise AudioError(f"samples must be 1-D or 2-D, got shape {arr.shape}")
    if arr.shape[1] == 1:
        return arr[:, 0]
    mono: Samples = arr.astype(np.float64).mean(axis=1)
    return np.rint(mono).astype(np.int16) if arr.dtype == np.int16 else mono.astype(arr.dtype)


# --- resampling -----------------------------------------------------------------------

#: libsoxr's "HQ" recipe (20-bit, linear phase): pass band to 91 % of the lower Nyquist frequency.
RESAMPLE_QUALITY: Final = "HQ"


class Resampler:
    """Streaming sample-rate conversion (libsoxr) of float32 or int16 samples, shape ``(frames,)``
    or ``(frames, channels)``, to float32. `process` + `flush` equals `resample` of the whole
    input (aligned, no added delay); while streaming, output lags input by the filter's delay
    (about 21 ms at 48 kHz -> 16 kHz). `flush` ends the stream and starts over."""

    def __init__(self, src_rate: int, dst_rate: int, channels: int = 1) -> None:
        if src_rate <= 0 or dst_rate <= 0:
            raise AudioError(f"sample rates must be positive, got {src_rate} -> {dst_rate}")
        self.src_rate = src_rate
        self.dst_rate = dst_rate
        self.channels = channels
        self._stream = soxr.ResampleStream(src_rate, dst_rate, channels, dtype="float32", quality=RESAMPLE_QUALITY)

    @property
    def latency_samples(self) -> int:
        """Input samples the streaming output lags behind now (what the filter holds back)."""
        return round(float(self._stream.delay()) * self.src_rate / self.dst_rate)

    def process(self, samples: Samples) -> Float32Array:
        """Feed samples (float32 or int16); returns the output samples now computable."""
        return self._run(samples, last=False)

    def flush(self) -> Float32Array:
        """Emit the remaining output (the input ends here) and reset."""
        empty = np.zeros((0,) if self.channels == 1 else (0, self.channels), dtype=np.float32)
        out = self._run(empty, last=True)
        self._stream.clear()
        return out

    def _run(self, samples: Samples, *, last: bool) -> Float32Array:
        x = as_float32(samples)
        if (x.ndim, x.shape[-1] if x.ndim == 2 else 1) != ((1, 1) if self.channels == 1 else (2, self.channels)):
            raise AudioError(f"Resampler for {self.channels} channel(s) got samples of shape {x.shape}")
        out: Float32Array = self._stream.resample_chunk(np.ascontiguousarray(x), last=last)
        return out


def resample(samples: Samples, src_rate: int, dst_rate: int) -> Samples:
    """One-shot resampling of mono or multi-channel samples (libsoxr); keeps the dtype (int16 or
    float32). Output length is ``len * dst / src`` rounded to the nearest sample."""
    arr = np.asarray(samples)
    if src_rate == dst_rate or arr.shape[0] == 0:
        return arr.copy()
    out = soxr.resample(np.ascontiguousarray(as_float32(arr)), src_rate, dst_rate, quality=RESAMPLE_QUALITY)
    return float32_to_int16(out) if arr.dtype == np.int16 else out.astype(arr.dtype, copy=False)


# --- chunk-level conversion -------------------------------------------------------------


def _cast(samples: Samples, width: int) -> Samples:
    return as_int16(samples) if width == 2 else as_float32(samples)


def convert(chunk: AudioChunk, fmt: AudioFormat) -> AudioChunk:
    """One-shot conversion of a whole chunk (an utterance, a file) to `fmt`.

    Channels: many -> 1 averages; 1 -> many duplicates; other changes are refused.
    """
    if chunk.format == fmt:
        return chunk
    samples = _convert_channels(chunk.samples, chunk.format.channels, fmt.channels)
    if chunk.format.rate != fmt.rate:
        samples = resample(as_float32(samples), chunk.format.rate, fmt.rate)
    return AudioChunk(_cast(samples, fmt.width), fmt, chunk.timestamp)


def _convert_channels(samples: Samples, src: int, dst: int) -> Samples:
    if src == dst:
        return samples
    if dst == 1:
        return to_mono(samples)
    if src == 1:
        return np.repeat(np.asarray(samples)[:, None], dst, axis=1)
    raise AudioError(f"cannot convert {src} channels to {dst}")


class FormatConverter:
    """Stateful converter for one stream of chunks (streaming resampler inside).

    Output timestamps are the first input timestamp plus the output sample count, so
    they stay exact across chunks. Call `flush` at the end of the stream.
    """

    def __init__(self, target: AudioFormat) -> None:
        self.target = target
        self._source: AudioFormat | None = None
        self._resampler: Resampler | None = None
        self._t0: float | None = None
        self._out_frames = 0

    def convert(self, chunk: AudioChunk) -> AudioChunk:
        if self._source is None:
            self._source = chunk.format
            self._t0 = chunk.timestamp
            if chunk.format.rate != self.target.rate:
                n = min(chunk.format.channels, self.target.channels)
                self._resampler = Resampler(chunk.format.rate, self.target.rate, n)
        elif chunk.format != self._source:
            raise AudioError(f"stream changed format mid-way: {self._source} -> {chunk.format}")
        samples = _convert_channels(
            chunk.samples, chunk.format.channels, min(chunk.format.channels, self.target.channels)
        )
        if self._resampler is not None:
            samples = self._resampler.process(samples)
        return self._emit(samples)

    def flush(self) -> AudioChunk | None:
        """Remaining resampler output, or None when there is nothing left."""
        if self._resampler is None:
            return None
        tail = self._resampler.flush()
        if tail.shape[0] == 0:
            return None
        return self._emit(tail)

    def _emit(self, samples: Samples) -> AudioChunk:
        samples = _convert_channels(samples, 1 if samples.ndim == 1 else samples.shape[1], self.target.channels)
        t0 = self._t0 if self._t0 is not None else 0.0
        out = AudioChunk(_cast(samples, self.target.width), self.target, t0 + self._out_frames / self.target.rate)
        self._out_frames += out.num_frames
        return out


# --- framing, joining, helpers ------------------------------------------------------------


class Framer:
    """Cuts a stream of chunks into frames of exactly `frame_samples` (e.g. 1280 for the
    wake word, 512 for VAD), each with its exact timestamp. Mono only; keeps the format."""

    def __init__(self, frame_samples: int) -> None:
        if frame_samples <= 0:
            raise AudioError(f"frame size must be positive, got {frame_samples}")
        self.frame_samples = frame_samples
        self._pending: Samples | None = None
        self._pending_t = 0.0
        self._format: AudioFormat | None = None

    def reset(self) -> None:
        self._pending = None
        self._format = None

    @property
    def pending_samples(self) -> int:
        return 0 if self._pending is None else int(self._pending.shape[0])

    def push(self, chunk: AudioChunk) -> list[AudioChunk]:
        if chunk.format.channels != 1:
            raise AudioError("Framer takes mono chunks; convert them first")
        if self._format is not None and chunk.format != self._format:
            raise AudioError(f"stream changed format mid-way: {self._format} -> {chunk.format}")
        self._format = chunk.format
        if self._pending is None or self._pending.shape[0] == 0:
            data: Samples = chunk.samples
            t0 = chunk.timestamp
        else:
            data = np.concatenate((self._pending, chunk.samples))
            t0 = self._pending_t
        n = self.frame_samples
        frames = [
            AudioChunk(data[i : i + n].copy(), chunk.format, t0 + i / chunk.format.rate)
            for i in range(0, data.shape[0] - n + 1, n)
        ]
        used = len(frames) * n
        self._pending = data[used:].copy()
        self._pending_t = t0 + used / chunk.format.rate
        return frames


def concat(chunks: Sequence[AudioChunk]) -> AudioChunk:
    """Join chunks of one format; the result has the first chunk's timestamp."""
    if not chunks:
        raise AudioError("nothing to concatenate")
    fmt = chunks[0].format
    for c in chunks:
        if c.format != fmt:
            raise AudioError(f"cannot concatenate {fmt} with {c.format}")
    return AudioChunk(np.concatenate([c.samples for c in chunks]), fmt, chunks[0].timestamp)


def silence(fmt: AudioFormat, seconds: float, timestamp: float = 0.0) -> AudioChunk:
    shape: tuple[int, ...] = (fmt.frames(seconds),) if fmt.channels == 1 else (fmt.frames(seconds), fmt.channels)
    return AudioChunk(np.zeros(shape, dtype=fmt.dtype), fmt, timestamp)


def rms_dbfs(samples: Samples) -> float:
    """RMS level in dB relative to full scale (-inf for digital silence)."""
    x = as_float32(samples).astype(np.float64)
    if x.size == 0:
        return -math.inf
    power = float(np.mean(x * x))
    return 10.0 * math.log10(power) if power > 0 else -math.inf


def split_chunk(chunk: AudioChunk, frames_per_chunk: int) -> Iterable[AudioChunk]:
    """Slice one chunk into consecutive chunks of at most `frames_per_chunk` frames."""
    for i in range(0, chunk.num_frames, frames_per_chunk):
        yield AudioChunk(chunk.samples[i : i + frames_per_chunk], chunk.format, chunk.timestamp + i / chunk.format.rate)
