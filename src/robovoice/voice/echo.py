"""Self-voice rejection, part 1: cancel the robot's own playback from the microphone.

The pipeline knows exactly what the speaker plays and when (`PlaybackReference`, filled by
the playback side in microphone stream time), so the echo can be *subtracted* instead of
merely tolerated:

- `EchoCanceller`: a partitioned-block frequency-domain adaptive filter (overlap-save,
  constrained NLMS; 16 ms blocks, 8 partitions = 128 ms of echo path) in plain numpy. It
  runs two filters ("two-path" echo cancellation, Ochiai et al.): a *background* filter
  that always adapts, and a *foreground* filter that produces the output and only takes the
  background's coefficients while they cancel better. When the person talks over the robot
  (double talk) the background filter is disturbed but the foreground keeps cancelling, so
  no double-talk detector thresholds need tuning.
- Every block also reports how loud the echo estimate and the residual are (`BlockStats`),
  which `frontend.EchoMeter` uses to decide whether speech heard during playback is the
  person's (barge-in) or what is left of the robot's own voice.

Pure numpy, no models; one instance per microphone stream (not thread-safe).
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass
from typing import Final

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, Float32Array, Samples, as_float32, convert

RATE: Final = MODEL_FORMAT.rate
_EPS: Final = 1e-10


class PlaybackReference:
    """What the speaker played, on the microphone's clock (16 kHz float32 samples).

    The playback side calls `place(chunk, start)` for audio that starts sounding at stream
    time `start` (seconds, the clock of the microphone's chunk timestamps) and
    `truncate(at)` when playback is stopped early (barge-in). The capture side reads
    `window(start, frames)`; silence where nothing played. Only the last `keep_s` seconds
    are kept. Thread-safe: the playback side writes on the event loop while the front end
    reads on its own thread.
    """

    def __init__(self, keep_s: float = 30.0) -> None:
        self._lock = threading.Lock()
        self._keep = round(keep_s * RATE)
        self._buf = np.zeros(0, dtype=np.float32)
        self._origin = 0  # absolute sample index of _buf[0]
        self._end = 0  # absolute index one past the last placed sample
        self._anchor: float | None = None  # stream time of absolute index 0

    def _index(self, t: float) -> int:
        if self._anchor is None:
            self._anchor = t
        return round((t - self._anchor) * RATE)

    def place(self, chunk: AudioChunk, start: float) -> float:
        """Add audio that starts playing at stream time `start`; returns its end time."""
        samples = as_float32(convert(chunk, MODEL_FORMAT.with_(width=4)).samples)
        with self._lock:
            return self._place(samples, start)

    def _place(self, samples: Float32Array, start: float) -> float:
        i0 = self._index(start)
        i1 = i0 + samples.shape[0]
        if i1 - self._origin > self._keep:  # forget what is older than keep_s before growing
            self._buf = self._buf[i1 - self._keep - self._origin :]
            self._origin = i1 - self._keep
        if i1 > self._origin + self._buf.shape[0]:
            grow = i1 - (self._origin + self._buf.shape[0])
            self._buf = np.concatenate((self._buf, np.zeros(grow, dtype=np.float32)))
        lo = max(i0, self._origin)
        if lo < i1:
            self._buf[lo - self._origin : i1 - self._origin] += samples[lo - i0 :]
        self._end = max(self._end, i1)
        self._trim()
        return self.time_of(i1)

    def truncate(self, at: float) -> None:
        """Nothing placed plays after stream time `at` (the speaker was stopped)."""
        with self._lock:
            self._truncate(at)

    def _truncate(self, at: float) -> None:
        i = self._index(at)
        if i < self._origin + self._buf.shape[0]:
            cut = max(0, i - self._origin)
            self._buf[cut:] = 0.0
        self._end = min(self._end, max(i, self._origin))

    def time_of(self, index: int) -> float:
        return (self._anchor or 0.0) + index / RATE

    @property
    def end_time(self) -> float | None:
        """When the last placed audio stops playing (None before anything was placed)."""
        with self._lock:
            return None if self._anchor is None else self.time_of(self._end)

    def playing(self, start: float, end: float) -> bool:
        """Whether anything was placed to play between `start` and `end`."""
        with self._lock:
            return self._playing(start, end)

    def _playing(self, start: float, end: float) -> bool:
        if self._anchor is None:
            return False
        i0, i1 = self._index(start), self._index(end)
        lo, hi = max(i0, self._origin), min(i1, self._origin + self._buf.shape[0])
        return hi > lo and bool(np.any(self._buf[lo - self._origin : hi - self._origin]))

    def window(self, start: float, frames: int) -> Float32Array:
        """`frames` reference samples from stream time `start` (zeros where nothing played)."""
        with self._lock:
            return self._window(start, frames)

    def _window(self, start: float, frames: int) -> Float32Array:
        out = np.zeros(frames, dtype=np.float32)
        if self._anchor is None:
            return out
        i0 = self._index(start)
        lo, hi = max(i0, self._origin), min(i0 + frames, self._origin + self._buf.shape[0])
        if hi > lo:
            out[lo - i0 : hi - i0] = self._buf[lo - self._origin : hi - self._origin]
        return out

    def _trim(self) -> None:
        excess = self._buf.shape[0] - self._keep
        if excess > 0:
            self._buf = self._buf[excess:]
            self._origin += excess


@dataclass(frozen=True, slots=True)
class BlockStats:
    """Levels of one processed block (mean power, linear): the microphone, the echo the
    filter predicted, and what is left after subtracting it; `reference` is the playback."""

    mic: float
    echo: float
    residual: float
    reference: float

    @property
    def erle_db(self) -> float:
        """Echo return loss enhancement of this block: how much quieter the residual is."""
        return 10.0 * math.log10((self.mic + _EPS) / (self.residual + _EPS))


class EchoCanceller:
    """Two-path partitioned-block FDAF (see the module docstring).

    `process(mic, reference)` takes equally long 16 kHz mono pieces (multiples of `block`)
    and returns the echo-cancelled microphone signal (same length, no added delay) plus
    stats per block. While the reference has been silent for longer than the filter
    length, blocks pass through untouched (no CPU spent, no drift).
    """

    def __init__(self, *, block: int = 256, partitions: int = 8, step: float = 0.5, smoothing: float = 0.9) -> None:
        self.block = block
        self.partitions = partitions
        self.step = step
        self._smoothing = smoothing
        bins = block + 1
        self._x_hist = np.zeros((partitions, bins), dtype=np.complex64)
        self._w_bg = np.zeros((partitions, bins), dtype=np.complex64)
        self._w_fg = np.zeros((partitions, bins), dtype=np.complex64)
        self._power = np.full(bins, 1e-4, dtype=np.float32)
        self._prev_x = np.zeros(block, dtype=np.float32)
        self._silent_blocks = partitions + 1
        self._fg_err = 0.0
        self._bg_err = 0.0
        self.copies = 0  # how often the background filter was promoted (for tests and logs)

    def reset(self) -> None:
        self.__init__(  # type: ignore[misc]  # reset = the state of a fresh instance, same settings
            block=self.block, partitions=self.partitions, step=self.step, smoothing=self._smoothing)

    @property
    def tail_s(self) -> float:
        """Length of echo path the filter models."""
        return self.block * self.partitions / RATE

    def process(self, mic: Samples, reference: Samples) -> tuple[Float32Array, list[BlockStats]]:
        """Cancel the echo of `reference` in `mic`: equally long 16 kHz mono blocks whose
        length is a multiple of `block` (the front end feeds 80 ms = 5 blocks)."""
        d_in = as_float32(mic)
        x_in = as_float32(reference)
        if d_in.shape != x_in.shape or d_in.ndim != 1 or d_in.shape[0] % self.block:
            raise ValueError(f"mic and reference must be equally long multiples of {self.block} samples, "
                             f"got {d_in.shape} and {x_in.shape}")
        n = self.block
        outs: list[Float32Array] = []
        stats: list[BlockStats] = []
        for i in range(0, d_in.shape[0], n):
            e, s = self._block(d_in[i : i + n], x_in[i : i + n])
            outs.append(e)
            stats.append(s)
        return np.concatenate(outs) if outs else np.zeros(0, dtype=np.float32), stats

    def _block(self, d: Float32Array, x: Float32Array) -> tuple[Float32Array, BlockStats]:
        n = self.block
        ref_power = float(np.mean(x * x))
        mic_power = float(np.mean(d * d))
        self._silent_blocks = self._silent_blocks + 1 if ref_power < 1e-9 else 0
        if self._silent_blocks > self.partitions:
            self._prev_x = x
            self._x_hist[:] = 0.0
            return d, BlockStats(mic_power, 0.0, mic_power, ref_power)

        big = np.fft.rfft(np.concatenate((self._prev_x, x))).astype(np.complex64)
        self._prev_x = x
        self._x_hist = np.roll(self._x_hist, 1, axis=0)
        self._x_hist[0] = big
        a = self._smoothing
        self._power = a * self._power + (1 - a) * (np.abs(big) ** 2).astype(np.float32)

        y_fg = np.fft.irfft(np.sum(self._w_fg * self._x_hist, axis=0), 2 * n)[n:].astype(np.float32)
        y_bg = np.fft.irfft(np.sum(self._w_bg * self._x_hist, axis=0), 2 * n)[n:].astype(np.float32)
        e_fg = d - y_fg
        e_bg = d - y_bg

        # background filter: constrained NLMS, always adapting
        err_spec = np.fft.rfft(np.concatenate((np.zeros(n, dtype=np.float32), e_bg))).astype(np.complex64)
        norm = self.partitions * self._power + 1e-6 * 2 * n
        grad = np.conj(self._x_hist) * err_spec[None, :] / norm[None, :]
        w = np.fft.irfft(self._w_bg + self.step * grad, 2 * n, axis=1)
        w[:, n:] = 0.0
        self._w_bg = np.fft.rfft(w, axis=1).astype(np.complex64)

        # two-path control: promote the background when it has cancelled better for a while,
        # restore it from the foreground when it went astray (double talk)
        p_fg, p_bg = float(np.mean(e_fg * e_fg)), float(np.mean(e_bg * e_bg))
        self._fg_err = 0.7 * self._fg_err + 0.3 * p_fg
        self._bg_err = 0.7 * self._bg_err + 0.3 * p_bg
        if self._bg_err < 0.8 * self._fg_err and p_bg < p_fg:
            self._w_fg = self._w_bg.copy()
            self._fg_err = self._bg_err
            self.copies += 1
        elif self._bg_err > 8.0 * self._fg_err + 1e-9:
            self._w_bg = self._w_fg.copy()
            self._bg_err = self._fg_err
        echo_power = float(np.mean(y_fg * y_fg))
        return e_fg, BlockStats(mic_power, echo_power, p_fg, ref_power)
