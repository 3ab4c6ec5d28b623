"""Measurements of the voice components (DESIGN.md §7), as functions returning frozen results.

- `frontend_cpu`: CPU time (process time, not wall) of the always-on front end, wake word +
  VAD, per second of audio -> % of one core (goal <= 3 %), plus per-frame costs.
- `stt_latency`: speech-to-text latency (wall and CPU) and word error rate on clips.
- `tts_first_audio`: text-to-speech time to the first audio chunk, and real-time factor.
- `wake_false_accepts`: wake-word detections per hour on audio without the wake phrase.

`run_all()` runs them on the committed fixtures (and a long negative WAV if given) with the
real models. Text helpers `normalize_text` and `word_error_rate` are here too.
"""

from __future__ import annotations

import logging
import re
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, concat, convert, split_chunk
from robovoice.audio.stt import Transcriber
from robovoice.audio.tts import Synthesizer
from robovoice.audio.vad import SpeechSegmenter, VADModel
from robovoice.audio.wake import WakeDecider, WakeDeciderConfig, WakeWordDetector, WakeWordSpotter
from robovoice.errors import AudioError

logger = logging.getLogger(__name__)


# --- statistics and text ---------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Stats:
    """Summary of a sample of measurements (same unit as the inputs)."""

    median: float
    p95: float
    mean: float
    max: float
    n: int

    @classmethod
    def of(cls, values: Sequence[float]) -> Stats:
        if not values:
            raise AudioError("no measurements")
        a = np.asarray(values, dtype=np.float64)
        return cls(
            median=float(np.median(a)),
            p95=float(np.percentile(a, 95)),
            mean=float(a.mean()),
            max=float(a.max()),
            n=int(a.size),
        )


def normalize_text(text: str) -> str:
    """Lower case, hyphens joined ("to-day" -> "today"), punctuation dropped, single spaces."""
    t = text.lower().replace("\u2019", "'")
    t = re.sub(r"(?<=\w)-(?=\w)", "", t)
    t = re.sub(r"[^\w\s']", " ", t)
    t = re.sub(r"(?<!\w)'|'(?!\w)", " ", t)
    return " ".join(t.split())


def word_error_rate(reference: str, hypothesis: str) -> float:
    """Word-level Levenshtein distance / reference length, after `normalize_text`."""
    ref = normalize_text(reference).split()
    hyp = normalize_text(hypothesis).split()
    if not ref:
        return 0.0 if not hyp else 1.0
    prev = list(range(len(hyp) + 1))
    for i, r in enumerate(ref, start=1):
        cur = [i] + [0] * len(hyp)
        for j, h in enumerate(hyp, start=1):
            cur[j] = min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (r != h))
        prev = cur
    return prev[-1] / len(ref)


# --- front end CPU ---------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class FrontEndCpu:
    """`core_percent`: CPU seconds per second of audio x 100, measured over blocks of
    `block_s`. `wake_ms_per_80ms` / `vad_ms_per_80ms`: CPU time that wake word detection
    (one 80 ms frame) and VAD + end-pointing (2.5 Silero frames) take per 80 ms of audio,
    including the framing/decision glue."""

    audio_s: float
    block_s: float
    core_percent: Stats
    wake_ms_per_80ms: Stats
    vad_ms_per_80ms: Stats


def frontend_cpu(audio: AudioChunk, detector: WakeWordDetector, vad: VADModel, *, block_s: float = 5.0) -> FrontEndCpu:
    """Feed all of `audio` (any format; converted to 16 kHz mono first, not timed) through a
    `WakeWordSpotter` and a `SpeechSegmenter` in 80 ms chunks, as the pipeline does, timing
    process CPU time (all threads of this process)."""
    audio = convert(audio, MODEL_FORMAT)
    spotter = WakeWordSpotter(detector)
    segmenter = SpeechSegmenter(vad)
    spotter.reset()
    segmenter.reset()
    chunks = list(split_chunk(audio, 1280))
    per_block = max(1, round(block_s / 0.08))
    wake_ms: list[float] = []
    vad_ms: list[float] = []
    block_percent: list[float] = []
    clock = time.process_time_ns
    for start in range(0, len(chunks) - per_block + 1, per_block):
        block = chunks[start : start + per_block]
        t_block = clock()
        for chunk in block:
            t0 = clock()
            spotter.feed(chunk)
            t1 = clock()
            segmenter.feed(chunk)
            t2 = clock()
            wake_ms.append((t1 - t0) / 1e6)
            vad_ms.append((t2 - t1) / 1e6)
        seconds = sum(c.duration_s for c in block)
        block_percent.append((clock() - t_block) / 1e9 / seconds * 100)
    if not block_percent:
        raise AudioError(f"need at least {block_s} s of audio")
    return FrontEndCpu(
        audio_s=len(block_percent) * per_block * 0.08,
        block_s=per_block * 0.08,
        core_percent=Stats.of(block_percent),
        wake_ms_per_80ms=Stats.of(wake_ms),
        vad_ms_per_80ms=Stats.of(vad_ms),
    )


# --- speech-to-text ----------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class LabelledAudio:
    id: str
    audio: AudioChunk
    text: str


@dataclass(frozen=True, slots=True)
class SttResult:
    id: str
    reference: str
    hypothesis: str
    wer: float
    audio_s: float
    latency_s: float
    cpu_s: float


@dataclass(frozen=True, slots=True)
class SttReport:
    """`wer`: total word errors / total reference words; latency per call (wall, s)."""

    name: str
    wer: float
    latency_s: Stats
    cpu_s: Stats
    real_time_factor: Stats
    results: tuple[SttResult, ...]


def stt_latency(name: str, transcriber: Transcriber, clips: Sequence[LabelledAudio], *, repeats: int = 3) -> SttReport:
    """Transcribe each clip `repeats` times (latency from every call, WER from the first)."""
    results: list[SttResult] = []
    latencies: list[float] = []
    cpus: list[float] = []
    rtfs: list[float] = []
    errors = 0.0
    words = 0
    for c in clips:
        first: SttResult | None = None
        for _ in range(repeats):
            t0, c0 = time.perf_counter(), time.process_time()
            text = transcriber.transcribe(c.audio).text
            latency, cpu = time.perf_counter() - t0, time.process_time() - c0
            latencies.append(latency)
            cpus.append(cpu)
            rtfs.append(latency / c.audio.duration_s)
            if first is None:
                first = SttResult(c.id, c.text, text, word_error_rate(c.text, text), c.audio.duration_s, latency, cpu)
        assert first is not None
        results.append(first)
        n = len(normalize_text(c.text).split())
        errors += first.wer * n
        words += n
    return SttReport(
        name=name,
        wer=errors / max(1, words),
        latency_s=Stats.of(latencies),
        cpu_s=Stats.of(cpus),
        real_time_factor=Stats.of(rtfs),
        results=tuple(results),
    )


# --- text-to-speech ----------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class TtsReport:
    """`first_audio_s`: call -> first chunk of `synthesize_stream` (wall); `total_s`: call ->
    all chunks; `real_time_factor`: total time / audio duration."""

    first_audio_s: Stats
    total_s: Stats
    real_time_factor: Stats


def tts_first_audio(synth: Synthesizer, texts: Sequence[str], *, repeats: int = 3) -> TtsReport:
    first: list[float] = []
    total: list[float] = []
    rtf: list[float] = []
    for _ in range(repeats):
        for text in texts:
            t0 = time.perf_counter()
            t_first: float | None = None
            duration = 0.0
            for chunk in synth.synthesize_stream(text):
                if t_first is None:
                    t_first = time.perf_counter() - t0
                duration += chunk.duration_s
            elapsed = time.perf_counter() - t0
            if t_first is None:
                raise AudioError(f"no audio for {text!r}")
            first.append(t_first)
            total.append(elapsed)
            rtf.append(elapsed / duration)
    return TtsReport(first_audio_s=Stats.of(first), total_s=Stats.of(total), real_time_factor=Stats.of(rtf))


# --- wake word false accepts ---------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class FalseAcceptReport:
    audio_h: float
    accepts: int
    per_hour: float
    timestamps_s: tuple[float, ...]
    max_score: float
    threshold: float


def wake_false_accepts(
    audio: AudioChunk, detector: WakeWordDetector, config: WakeDeciderConfig | None = None
) -> FalseAcceptReport:
    """Stream `audio` (no wake phrase in it) through detector + decider; count detections."""
    audio = convert(audio, MODEL_FORMAT)
    decider = WakeDecider(config)
    spotter = WakeWordSpotter(detector, decider)
    spotter.reset()
    stamps: list[float] = []
    top = 0.0
    for chunk in split_chunk(audio, detector.frame_samples):
        stamps += [e.timestamp for e in spotter.feed(chunk)]
        top = max(top, spotter.last_score)
    hours = audio.duration_s / 3600
    return FalseAcceptReport(
        audio_h=hours,
        accepts=len(stamps),
        per_hour=len(stamps) / hours if hours else 0.0,
        timestamps_s=tuple(stamps),
        max_score=top,
        threshold=decider.threshold,
    )


# --- all together ----------------------------------------------------------------------------------------

TTS_TEXTS = (
    "Okay.",
    "I am driving to the kitchen now.",
    "Your battery is at eighty percent and charging. Do you want me to go anywhere?",
)


def load_fixture_clips(folder: Path) -> list[LabelledAudio]:
    """The clips listed in ``<folder>/clips.json`` (see scripts/make_audio_fixtures.py)."""
    import json

    from robovoice.audio.wav import read_wav

    items: list[dict[str, Any]] = json.loads((folder / "clips.json").read_text(encoding="utf-8"))
    return [LabelledAudio(i["id"], read_wav(folder / f"{i['id']}.wav"), i["text"]) for i in items]


def run_all(
    fixtures: Path = Path("tests/data/audio"),
    *,
    negative_wav: Path | None = None,
    whisper: bool = False,
    repeats: int = 3,
    progress: Callable[[str], None] | None = None,
) -> dict[str, Any]:
    """Every benchmark with the real models; JSON-ready dict. `whisper` adds faster-whisper
    (must be installed). The false-accept rate needs `negative_wav` (>= 10 min advised)."""
    from robovoice.audio.stt import MoonshineTranscriber, WhisperTranscriber
    from robovoice.audio.tts import PiperSynthesizer
    from robovoice.audio.vad import SileroVAD
    from robovoice.audio.wake import OpenWakeWordDetector
    from robovoice.audio.wav import read_wav

    say = progress or (lambda _msg: None)
    clips = load_fixture_clips(fixtures)
    out: dict[str, Any] = {}
    # the default detector scores all 8 offsets; one offset (openWakeWord's own) is the baseline
    detector, one_offset, vad = OpenWakeWordDetector(), OpenWakeWordDetector(phases=1), SileroVAD()
    clips_s = sum(c.audio.duration_s for c in clips)
    loop = concat([convert(c.audio, MODEL_FORMAT) for c in clips] * max(1, round(60 / clips_s)))
    say("front end CPU")
    out["frontend_cpu"] = asdict(frontend_cpu(loop, detector, vad))
    out["frontend_cpu_one_offset"] = asdict(frontend_cpu(loop, one_offset, vad))
    say("speech-to-text (Moonshine)")
    stts: list[tuple[str, Callable[[], Transcriber]]] = [("moonshine-base-en", MoonshineTranscriber)]
    if whisper:
        stts.append(("whisper-tiny.en", WhisperTranscriber))
    out["stt"] = {}
    for name, make in stts:
        t0 = time.perf_counter()
        model = make()
        load_s = time.perf_counter() - t0
        report = asdict(stt_latency(name, model, clips, repeats=repeats))
        report["load_s"] = load_s
        out["stt"][name] = report
        say(f"speech-to-text ({name}) done")
    say("text-to-speech")
    t0 = time.perf_counter()
    synth = PiperSynthesizer()
    out["tts"] = {"load_s": time.perf_counter() - t0, **asdict(tts_first_audio(synth, TTS_TEXTS, repeats=repeats))}
    if negative_wav is not None:
        say("wake word false accepts")
        negative = read_wav(negative_wav)
        out["wake_false_accepts"] = asdict(wake_false_accepts(negative, detector))
        out["wake_false_accepts_one_offset"] = asdict(wake_false_accepts(negative, one_offset))
        say("front end CPU on the audio without the wake phrase")
        out["frontend_cpu_negative"] = asdict(frontend_cpu(negative, detector, vad))
        out["frontend_cpu_negative_one_offset"] = asdict(frontend_cpu(negative, one_offset, vad))
    return out
