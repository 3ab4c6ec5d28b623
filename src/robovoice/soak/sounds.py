"""What the soak's room hears: background material (television-like talk without the wake
phrase, music-like tones, pink noise) and the spoken commands, each made once.

Television talk is synthesised with espeak-ng (several accents, like the eval's negative
clips) when the binary is there, and with Piper otherwise; commands are spoken with the
robot's own Piper voice (`VoiceModels.tts`), like the eval clips. Everything is 16 kHz mono
float32, cached per text, and levels are set here (dBFS of the active speech).
"""

from __future__ import annotations

import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Final

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, Float32Array, as_float32, convert, float32_to_int16
from robovoice.audio.tts import Synthesizer
from robovoice.audio.wav import read_wav

RATE: Final = MODEL_FORMAT.rate

#: Television / people talking nearby: no wake phrase, no "stop" (a stop needs no wake word).
TV_LINES: Final = (
    "Good evening, and welcome to the news at six.",
    "And now the weather. Tomorrow will be cloudy, with showers in the north.",
    "The council has approved the new bridge over the river.",
    "Add two cups of flour and a pinch of salt, then mix well.",
    "In other news, a rare bird was spotted on the coast.",
    "The home team scored twice in the second half.",
    "Prices at the supermarket rose again this month.",
    "Remember to water the tomatoes before you go on holiday.",
    "The museum opens a new exhibition about old maps on Friday.",
    "Traffic is heavy on the ring road this morning.",
    "She said the train was late again, so they took a taxi.",
    "Scientists found a new species of frog in the rainforest.",
)
TV_VOICES: Final = ("en-us:170", "en-gb:165", "en-gb-scotland:160", "en-us+f3:150", "en-029:150")


def _level(x: Float32Array, dbfs: float) -> Float32Array:
    """Scale `x` so its loud frames (speech without pauses) sit at `dbfs`."""
    frame = 320
    n = len(x) // frame
    if n == 0:
        return x
    power = np.mean(x[: n * frame].astype(np.float64).reshape(n, frame) ** 2, axis=1)
    active = power[power >= power.max() * 1e-3]
    rms = float(np.sqrt(np.mean(active))) if active.size else 0.0
    return (x * (10 ** (dbfs / 20) / rms)).astype(np.float32) if rms > 0 else x


def pink_noise(seconds: float, rng: np.random.Generator, dbfs: float = -40.0) -> Float32Array:
    n = max(1, round(seconds * RATE))
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, 1 / RATE)
    spec[1:] /= np.sqrt(f[1:])
    spec[0] = 0
    x = np.fft.irfft(spec, n)
    x *= 10 ** (dbfs / 20) / (np.sqrt(np.mean(x * x)) + 1e-12)
    return x.astype(np.float32)


def music(seconds: float, rng: np.random.Generator, dbfs: float = -30.0) -> Float32Array:
    """Music-like tones: chords of harmonics, notes of 0.25-0.6 s with attack and decay."""
    out: list[Float32Array] = []
    total = round(seconds * RATE)
    made = 0
    while made < total:
        n = round(rng.uniform(0.25, 0.6) * RATE)
        t = np.arange(n) / RATE
        root = 220.0 * 2 ** (int(rng.integers(0, 12)) / 12)
        note = np.zeros(n)
        for ratio in (1.0, 1.25, 1.5):
            for h in (1, 2, 3):
                note += np.sin(2 * np.pi * root * ratio * h * t) / h
        note *= np.minimum(1.0, t / 0.02) * np.exp(-3.0 * t)
        out.append(note.astype(np.float32))
        made += n
    return _level(np.concatenate(out)[:total], dbfs)


class SoakSounds:
    """See the module docstring. `voice`: the robot's Piper voice (for commands, and for the
    television when espeak-ng is missing)."""

    def __init__(self, voice: Synthesizer, rng: np.random.Generator) -> None:
        self._voice = voice
        self._rng = rng
        self._espeak = shutil.which("espeak-ng")
        self._said: dict[str, Float32Array] = {}
        self._tv: list[Float32Array] = []

    @property
    def tv_voice(self) -> str:
        return "espeak-ng" if self._espeak else "piper"

    def command(self, text: str, dbfs: float = -22.0) -> AudioChunk:
        """`text` in the robot's Piper voice, 0.2 s of silence after it."""
        x = self._said.get(text)
        if x is None:
            x = _level(as_float32(convert(self._voice.synthesize(text), MODEL_FORMAT).samples), dbfs)
            x = np.concatenate([x, np.zeros(round(0.2 * RATE), dtype=np.float32)])
            self._said[text] = x
        return _chunk(x)

    def _tv_lines(self) -> list[Float32Array]:
        if not self._tv:
            for i, line in enumerate(TV_LINES):
                x = self._espeak_line(line, TV_VOICES[i % len(TV_VOICES)]) if self._espeak else \
                    as_float32(convert(self._voice.synthesize(line), MODEL_FORMAT).samples)
                self._tv.append(_level(x, -28.0))
        return self._tv

    def _espeak_line(self, text: str, voice: str) -> Float32Array:
        assert self._espeak is not None
        name, _, wpm = voice.partition(":")
        with tempfile.TemporaryDirectory() as tmp:
            wav = Path(tmp) / "tv.wav"
            subprocess.run([self._espeak, "-v", name, "-s", wpm, "-w", str(wav), text], check=True,
                           capture_output=True, timeout=60)
            return as_float32(convert(read_wav(wav), MODEL_FORMAT).samples)

    def background(self, kind: str, seconds: float) -> AudioChunk:
        """`seconds` of ``tv`` (talk with pauses over a faint noise), ``music`` or ``pink`` noise."""
        rng = self._rng
        n = round(seconds * RATE)
        if kind == "tv":
            lines = self._tv_lines()
            parts: list[Float32Array] = []
            made = 0
            while made < n:
                line = lines[int(rng.integers(len(lines)))]
                pause = np.zeros(round(rng.uniform(0.3, 1.5) * RATE), dtype=np.float32)
                parts += [line, pause]
                made += len(line) + len(pause)
            x = np.concatenate(parts)[:n] + pink_noise(seconds, rng, -50.0)[:n]
        elif kind == "music":
            x = music(seconds, rng)
        elif kind == "pink":
            x = pink_noise(seconds, rng, -38.0)
        else:
            raise ValueError(f"background kind {kind!r}: use tv, music or pink")
        return _chunk(x.astype(np.float32))


def _chunk(x: Float32Array) -> AudioChunk:
    return AudioChunk(float32_to_int16(np.clip(x, -1.0, 1.0)), MODEL_FORMAT)
