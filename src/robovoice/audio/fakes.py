"""First-class fakes of the model seams (DESIGN.md §4.1), for tests and for running the
pipeline without models. WAV sources/sinks (`robovoice.audio.wav`) are the I/O fakes."""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from typing import Final

import numpy as np

from robovoice.audio.format import AudioChunk, AudioFormat, Samples, as_float32, float32_to_int16
from robovoice.audio.stt import Transcript
from robovoice.audio.vad import VAD_FRAME_SAMPLES
from robovoice.audio.wake import WAKE_FRAME_SAMPLES
from robovoice.errors import AudioError

_PIPER_RATE: Final = 22050


class ScriptedWakeDetector:
    """Returns the given scores, one per 80 ms frame, then `default` forever."""

    frame_samples: int = WAKE_FRAME_SAMPLES

    def __init__(self, scores: Iterable[float] = (), default: float = 0.0) -> None:
        self._scores = list(scores)
        self._default = default
        self.frames_seen = 0
        self.resets = 0

    def process(self, frame: Samples) -> float:
        i = self.frames_seen
        self.frames_seen += 1
        return self._scores[i] if i < len(self._scores) else self._default

    def reset(self) -> None:
        self.resets += 1


class ToneWakeDetector:
    """A wake word "model" that hears a tone (1 kHz by default): score 0.99 on frames where the
    tone carries most of the energy, else 0. Synthetic test audio marks the wake phrase with it."""

    frame_samples: int = WAKE_FRAME_SAMPLES

    def __init__(self, tone_hz: float = 1000.0, rate: int = 16_000) -> None:
        t = np.arange(WAKE_FRAME_SAMPLES) / rate
        self._c = np.cos(2 * np.pi * tone_hz * t)
        self._s = np.sin(2 * np.pi * tone_hz * t)

    def process(self, frame: Samples) -> float:
        x = as_float32(frame).astype(np.float64)
        total = float(np.sum(x * x)) + 1e-12
        tone = (float(np.dot(x, self._c)) ** 2 + float(np.dot(x, self._s)) ** 2) * 2 / len(x)
        return 0.99 if total > 1e-4 and tone / total > 0.5 else 0.0

    def reset(self) -> None:
        return None


class EnergyVAD:
    """A model-free VAD: speech probability from the frame's RMS level, a logistic curve
    centred on `threshold_dbfs` (6 dB above it -> ~0.95). Good enough for clean test audio."""

    frame_samples: int = VAD_FRAME_SAMPLES

    def __init__(self, threshold_dbfs: float = -45.0) -> None:
        self.threshold_dbfs = threshold_dbfs

    def probability(self, frame: Samples) -> float:
        x = as_float32(frame).astype(np.float64)
        power = float(np.mean(x * x)) if x.size else 0.0
        level = 10.0 * math.log10(power) if power > 1e-12 else -120.0
        return 1.0 / (1.0 + math.exp(-(level - self.threshold_dbfs) / 2.0))

    def reset(self) -> None:
        return None


class ScriptedTranscriber:
    """Returns the given texts in order, one per call (raises AudioError when exhausted)."""

    def __init__(self, texts: Iterable[str]) -> None:
        self._texts = iter(list(texts))
        self.calls: list[AudioChunk] = []
        self.hints: list[str] = []

    def transcribe(self, audio: AudioChunk, hint: str = "") -> Transcript:
        self.calls.append(audio)
        self.hints.append(hint)
        try:
            text = next(self._texts)
        except StopIteration:
            raise AudioError("ScriptedTranscriber has no more texts") from None
        return Transcript(text=text, duration_s=audio.duration_s)


class ToneSynthesizer:
    """Speaks nothing but a soft tone, `seconds_per_char` long per character of text, one
    chunk per call (the sentence splitting is the caller's); 22 050 Hz like Piper."""

    def __init__(self, seconds_per_char: float = 0.05, frequency: float = 440.0, rate: int = _PIPER_RATE) -> None:
        self._format = AudioFormat(rate=rate, width=2, channels=1)
        self._spc = seconds_per_char
        self._freq = frequency
        self.texts: list[str] = []

    @property
    def format(self) -> AudioFormat:
        return self._format

    def synthesize(self, text: str) -> AudioChunk:
        self.texts.append(text)
        n = round(len(text.strip()) * self._spc * self._format.rate)
        t = np.arange(n, dtype=np.float32) / self._format.rate
        return AudioChunk(float32_to_int16(0.2 * np.sin(2 * np.pi * self._freq * t)), self._format)

    def synthesize_stream(self, text: str) -> Iterator[AudioChunk]:
        chunk = self.synthesize(text)
        if chunk.num_frames:
            yield chunk
