"""Self-describing audio values and every conversion between formats (DESIGN.md §4.4).

`AudioFormat` says what the numbers in an `AudioChunk` mean; everything that changes
format -- sample type (int16 <-> float32), channel count (stereo -> mono) and sample
rate (any rate -> 16 kHz for wake word/VAD/STT, 22.05 kHz TTS -> output device rate)
-- lives in this one module, implemented with numpy only.

Resampling is a polyphase windowed-sinc (Kaiser) interpolator over the rational ratio
``dst/src`` (the same family as ``scipy.signal.resample_poly``), streaming-capable so a
microphone at 48 kHz can be converted chunk by chunk without seams. Defaults: pass band
to 0.9 x the lower Nyquist frequency, >= 80 dB stop band (measured in tests/audio).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Final, TypeAlias

import numpy as np
import numpy.typing as npt

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


@dataclass(frozen=True, slots=True)
class ResamplerDesign:
    """Filter parameters: pass band edge as a fraction of the lower Nyquist frequency,
    half-length in zero crossings of the low-pass sinc, and the Kaiser window beta."""

    rolloff: float = 0.9
    zero_crossings: int = 16
    kaiser_beta: float = 8.0


_DEFAULT_DESIGN: Final = ResamplerDesign()


class Resampler:
    """Streaming rational-ratio resampler for mono float32 audio.

    Output sample n is the band-limited value of the input at time ``n * src / dst``
    (no added delay in the result of `process` + `flush`; while streaming, output lags
    input by the filter half-length, ``zero_crossings / (0.9 * min(1, dst/src))`` input
    samples, e.g. 1.7 ms for 48 kHz -> 16 kHz).
    """

    _BLOCK = 4096

    def __init__(self, src_rate: int, dst_rate: int, design: ResamplerDesign = _DEFAULT_DESIGN) -> None:
        if src_rate <= 0 or dst_rate <= 0:
            raise AudioError(f"sample rates must be positive, got {src_rate} -> {dst_rate}")
        g = math.gcd(src_rate, dst_rate)
        self.src_rate = src_rate
        self.dst_rate = dst_rate
        self._up = dst_rate // g
        self._down = src_rate // g
        cutoff = design.rolloff * min(1.0, self._up / self._down)  # in cycles per input Nyquist
        self._half = math.ceil(design.zero_crossings / cutoff)
        taps = 2 * self._half
        phases = np.arange(self._up, dtype=np.float64)[:, None] / self._up
        tau = phases + (self._half - 1) - np.arange(taps, dtype=np.float64)[None, :]
        window = np.i0(design.kaiser_beta * np.sqrt(np.clip(1.0 - (tau / self._half) ** 2, 0.0, 1.0)))
        table = cutoff * np.sinc(cutoff * tau) * window / np.i0(design.kaiser_beta)
        table /= table.sum(axis=1, keepdims=True)  # unity DC gain for every phase
        self._table = table.astype(np.float32)
        self.reset()

    @property
    def latency_samples(self) -> int:
        """Input samples the streaming output lags behind (filter half-length)."""
        return self._half

    def reset(self) -> None:
        self._buf: Float32Array = np.zeros(self._half, dtype=np.float32)
        self._buf_start = -self._half  # absolute input index of _buf[0]
        self._total_in = 0
        self._next_out = 0

    def process(self, samples: Samples) -> Float32Array:
        """Feed mono samples (float32 or int16); returns the output samples now computable."""
        x = as_float32(samples)
        if x.ndim != 1:
            raise AudioError("Resampler takes mono samples; call to_mono() first")
        if self._up == self._down:
            return x.copy()
        self._buf = np.concatenate((self._buf, x))
        self._total_in += x.shape[0]
        last_input = self._total_in - 1 - self._half  # highest i0 usable
        if last_input < 0:
            return np.zeros(0, dtype=np.float32)
        n_max = ((last_input + 1) * self._up - 1) // self._down
        return self._emit(n_max + 1)

    def flush(self) -> Float32Array:
        """Emit the remaining output (as if followed by silence) and reset."""
        if self._up == self._down:
            self.reset()
            return np.zeros(0, dtype=np.float32)
        n_total = -(-self._total_in * self._up // self._down)  # ceil
        self._buf = np.concatenate((self._buf, np.zeros(self._half + 1, dtype=np.float32)))
        out = self._emit(n_total)
        self.reset()
        return out

    def _emit(self, n_end: int) -> Float32Array:
        if n_end <= self._next_out:
            return np.zeros(0, dtype=np.float32)
        taps = 2 * self._half
        offsets = np.arange(taps, dtype=np.int64)
        parts: list[Float32Array] = []
        for start in range(self._next_out, n_end, self._BLOCK):
            n = np.arange(start, min(start + self._BLOCK, n_end), dtype=np.int64)
            pos = n * self._down
            i0 = pos // self._up
            phase = pos % self._up
            idx = (i0 - self._half + 1 - self._buf_start)[:, None] + offsets[None, :]
            parts.append(np.einsum("nk,nk->n", self._buf[idx], self._table[phase]).astype(np.float32))
        self._next_out = n_end
        # drop input no longer needed by the next output
        keep_from = (self._next_out * self._down) // self._up - self._half + 1
        drop = keep_from - self._buf_start
        if drop > 0:
            self._buf = self._buf[drop:]
            self._buf_start = keep_from
        return np.concatenate(parts)


def resample(samples: Samples, src_rate: int, dst_rate: int, design: ResamplerDesign = _DEFAULT_DESIGN) -> Samples:
    """One-shot resampling of mono or multi-channel samples; keeps the dtype (int16 or float32).

    Output length is ``ceil(len * dst / src)``.
    """
    arr = np.asarray(samples)
    if src_rate == dst_rate:
        return arr.copy()
    if arr.ndim == 2:
        channels = [resample(arr[:, c], src_rate, dst_rate, design) for c in range(arr.shape[1])]
        return np.stack(channels, axis=1)
    rs = Resampler(src_rate, dst_rate, design)
    out = np.concatenate((rs.process(arr), rs.flush()))
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
        self._resamplers: list[Resampler] = []
        self._t0: float | None = None
        self._out_frames = 0

    def convert(self, chunk: AudioChunk) -> AudioChunk:
        if self._source is None:
            self._source = chunk.format
            self._t0 = chunk.timestamp
            if chunk.format.rate != self.target.rate:
                n = min(chunk.format.channels, self.target.channels)
                self._resamplers = [Resampler(chunk.format.rate, self.target.rate) for _ in range(n)]
        elif chunk.format != self._source:
            raise AudioError(f"stream changed format mid-way: {self._source} -> {chunk.format}")
        samples = _convert_channels(
            chunk.samples, chunk.format.channels, min(chunk.format.channels, self.target.channels)
        )
        if self._resamplers:
            if samples.ndim == 1:
                samples = self._resamplers[0].process(samples)
            else:
                samples = np.stack([r.process(samples[:, c]) for c, r in enumerate(self._resamplers)], axis=1)
        return self._emit(samples)

    def flush(self) -> AudioChunk | None:
        """Remaining resampler output, or None when there is nothing left."""
        if not self._resamplers:
            return None
        if len(self._resamplers) == 1:
            tail: Samples = self._resamplers[0].flush()
        else:
            tail = np.stack([r.flush() for r in self._resamplers], axis=1)
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
