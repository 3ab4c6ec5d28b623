"""Measures the shorter end-of-turn silence on recorded clips: how often it cuts a speaker off
compared with the full silence, and how much silence it saves.

    python -m robovoice.voice.speculate_eval tests/data/eval/audio.jsonl [--early-ms 300] [--json]
    python -m robovoice.voice.speculate_eval --prefill-ab --turns 8   # prefill on/off, `bench_local`
    python -m robovoice.voice.speculate_eval --head-start-ms 200 --turns 8   # the model alone

Each clip goes through Silero VAD and the `Endpointer` the way the listener feeds them (80 ms
chunks; a pause is the first quiet chunk of an utterance), twice:

- the full rule: the end of turn after ``end_of_turn_silence_ms`` (500) of silence;
- the early rule: at each pause the utterance so far is transcribed (Whisper tiny.en with the
  sim robot's command hint, as the pipeline does) and, when `completeness.is_complete` says the
  words (wake phrase removed) are complete, the shorter silence is allowed at once, as if the
  transcript were instant (the most cutting case).

A *cut-off* is an utterance end followed by more speech in the same clip (each clip is one
turn of one speaker). Silence saved, per utterance the early rule ended: the full rule's
decision time minus the early one's, ideal (instant transcript) and with the transcript's
measured time (the early end cannot come before the transcript does).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, convert
from robovoice.audio.stt import Transcriber
from robovoice.audio.vad import Endpointer, EndpointerConfig, SpeechEnded, SpeechStarted
from robovoice.audio.wav import read_wav
from robovoice.voice.completeness import is_complete
from robovoice.voice.utterance import strip_wake_words

CHUNK = 1280  # the listener's 80 ms frame
VAD_FRAME = 512


@dataclass(slots=True)
class ClipRun:
    """One clip under one rule: utterance (start, end, decided-at) and pauses' transcripts."""

    utterances: list[tuple[float, float, float, bool]] = field(default_factory=list)  # start, end, decided, early
    pauses: list[tuple[float, str, float, bool]] = field(default_factory=list)  # at, text, stt seconds, complete

    @property
    def cut_offs(self) -> int:
        return max(0, len(self.utterances) - 1)


def probabilities(audio: AudioChunk) -> np.ndarray:
    """Silero's speech probability of every 32 ms frame of `audio` (a fresh model state)."""
    from robovoice.audio.vad import SileroVAD

    vad = SileroVAD()
    n = len(audio.samples) // VAD_FRAME
    return np.array([vad.probability(audio.samples[k * VAD_FRAME : (k + 1) * VAD_FRAME]) for k in range(n)])


def run_rule(audio: AudioChunk, probs: np.ndarray, stt: Transcriber | None, hint: str, early_s: float | None,
             full_s: float) -> ClipRun:
    """Replay the frames into an endpointer, as the listener does (see the module docstring)."""
    ep = Endpointer(EndpointerConfig(end_silence_s=full_s))
    run = ClipRun()
    onset: float | None = None
    paused = False
    frames_done = 0
    rate = MODEL_FORMAT.rate
    for chunk_end in range(CHUNK, len(audio.samples) + 1, CHUNK):
        now = chunk_end / rate
        while (frames_done + 1) * VAD_FRAME <= chunk_end:  # the VAD frames this chunk completes
            k = frames_done
            frame = audio.samples[k * VAD_FRAME : (k + 1) * VAD_FRAME]
            for event in ep.update(float(probs[k]), frame, k * VAD_FRAME / rate):
                if isinstance(event, SpeechStarted):
                    onset, paused = event.timestamp, False
                elif isinstance(event, SpeechEnded):
                    run.utterances.append((event.start, event.end, now, event.early))
                    onset = None
            frames_done += 1
        if onset is None or not ep.in_speech or frames_done == 0:
            continue
        if probs[frames_done - 1] >= ep.config.stop_threshold:
            paused = False
            continue
        if paused or stt is None:
            continue
        paused = True
        start = max(0, round((onset - ep.config.pre_roll_s) * rate))
        so_far = AudioChunk(audio.samples[start:chunk_end], MODEL_FORMAT, start / rate)
        began = time.perf_counter()
        text = strip_wake_words(stt.transcribe(so_far, hint).text)
        took = time.perf_counter() - began
        complete = is_complete(text)
        run.pauses.append((now, text, took, complete))
        if complete and early_s is not None:
            ep.allow_early_end(onset, now, early_s)
    for event in ep.flush():
        if isinstance(event, SpeechEnded):
            run.utterances.append((event.start, event.end, len(audio.samples) / rate, event.early))
    return run


@dataclass(slots=True)
class Report:
    clips: int = 0
    cut_offs_full: int = 0
    cut_offs_early: int = 0
    early_ends: int = 0
    early_ends_cutting: list[str] = field(default_factory=list)  # clip ids where an early end cut speech
    saved_ideal_ms: list[float] = field(default_factory=list)
    saved_measured_ms: list[float] = field(default_factory=list)
    stt_ms: list[float] = field(default_factory=list)
    incomplete: list[str] = field(default_factory=list)  # "clip: text" of final pauses judged incomplete

    def summary(self) -> dict[str, object]:
        def p50(xs: list[float]) -> float | None:
            return round(statistics.median(xs), 1) if xs else None

        out = asdict(self)
        for name in ("saved_ideal_ms", "saved_measured_ms", "stt_ms"):
            out[name] = {"p50": p50(getattr(self, name)), "n": len(getattr(self, name))}
        return out


def measure(cases: Path, stt: Transcriber, hint: str, early_s: float, full_s: float) -> Report:
    report = Report()
    for line in cases.read_text(encoding="utf-8").splitlines():
        if not line.strip():
            continue
        case = json.loads(line)
        audio = convert(read_wav(cases.parent / case["audio"]), MODEL_FORMAT)
        probs = probabilities(audio)
        full = run_rule(audio, probs, None, hint, None, full_s)
        early = run_rule(audio, probs, stt, hint, early_s, full_s)
        report.clips += 1
        report.cut_offs_full += full.cut_offs
        report.cut_offs_early += early.cut_offs
        report.stt_ms += [p[2] * 1000 for p in early.pauses]
        for _start, end, decided, was_early in early.utterances:
            if not was_early:
                continue
            report.early_ends += 1
            same = [u for u in full.utterances if abs(u[1] - end) < 1e-6]
            if not same:  # the full rule went on past this end: the speaker was cut off
                report.early_ends_cutting.append(case["id"])
                continue
            report.saved_ideal_ms.append((same[0][2] - decided) * 1000)
            pause = max((p for p in early.pauses if p[0] <= decided + 1e-6), key=lambda p: p[0])
            ready = pause[0] + pause[2]  # the transcript's real arrival, in stream time
            grid = np.ceil(max(decided, ready) * MODEL_FORMAT.rate / CHUNK) * CHUNK / MODEL_FORMAT.rate
            report.saved_measured_ms.append(max(0.0, (same[0][2] - grid) * 1000))
        if early.pauses and not early.pauses[-1][3]:
            report.incomplete.append(f"{case['id']}: {early.pauses[-1][1]}")
    return report


async def sim_hint(wake_phrase: str) -> str:
    """The command hint the pipeline gives speech-to-text for the sim robot's tools."""
    from robovoice.assistant.connect import connect_robot
    from robovoice.config import RobotConfig
    from robovoice.voice.vocabulary import command_hint

    async with connect_robot(RobotConfig(address="sim://")) as link:
        return command_hint(wake_phrase, await link.tools.specs())


async def prefill_ab(turns: int) -> dict[str, object]:
    """`voice.bench.bench_local` (the all-local stack, real-time room) with the speculative
    prefill off, then on; the shorter silence is off in both, so only the prefill differs."""
    from robovoice.config import VoiceConfig
    from robovoice.voice import bench

    out: dict[str, object] = {}
    models = None
    for name, prefill in (("without_prefill", False), ("with_prefill", True)):
        if models is None:
            from robovoice.voice.models import load_voice_models

            models = await asyncio.to_thread(load_voice_models)
        result = await bench.bench_local(turns, models=models, naive=False,
                                         voice=VoiceConfig(early_end=False, speculative_prefill=prefill))
        out[name] = {k: result[k] for k in ("turns", "speech_end_to_first_audio_ms", "stages_from_speech_end",
                                            "stages_from_end_of_turn_decision", "machine")}
    return out


async def head_start(turns: int, head_start_s: float) -> dict[str, object]:
    """The embedded model alone, with the assistant's prompt and the sim robot's tools: from the
    start of a turn (= the end-of-turn decision, transcript in hand) to its first token, without
    a prefill and with one started `head_start_s` earlier (the silence left after the speculative
    transcript; negative: the prefill is let finish first, the best case). Each command runs
    both ways, alternating which goes first, each from the same cache (system prompt and tools
    evaluated, as for a fresh conversation). Deadlines are patient: a loaded machine measures,
    it does not fall back."""
    from robovoice.assistant.connect import connect_robot
    from robovoice.assistant.loop import Assistant
    from robovoice.assistant.metrics import TurnMetrics
    from robovoice.assistant.prompt import SYSTEM_PROMPT
    from robovoice.config import RobotConfig
    from robovoice.llm.base import Deadlines
    from robovoice.llm.local import LocalLlamaBackend
    from robovoice.voice.bench import LOCAL_COMMANDS

    local = LocalLlamaBackend(deadlines=Deadlines(connect_s=0.0, first_token_s=600, idle_s=300, total_s=1200))
    first_token: dict[str, list[float]] = {"without": [], "with": []}
    replayed = 0
    try:
        async with connect_robot(RobotConfig(address="sim://?speed=50")) as link:
            specs = await link.tools.specs()
            assistant = Assistant(local, link.tools)
            for i in range(turns):
                text = strip_wake_words(LOCAL_COMMANDS[i % len(LOCAL_COMMANDS)])
                for mode in ("with", "without") if i % 2 else ("without", "with"):
                    assistant.reset()
                    await local.warm_up(SYSTEM_PROMPT, specs)
                    guess = None
                    if mode == "with":
                        messages, tools = await assistant.first_request(text)
                        guess = asyncio.create_task(local.prefill(messages, tools))
                        if head_start_s < 0:
                            await guess
                        else:
                            await asyncio.sleep(head_start_s)
                    metrics = TurnMetrics()
                    await assistant.turn(text, metrics=metrics)
                    if guess is not None:
                        done = await guess
                        replayed += bool(done is not None and done.decoded_call)
                    first_token[mode].append(metrics.marks.get("first_token", float("nan")))
    finally:
        await local.aclose()

    def p(xs: list[float], q: float) -> float:
        return round(float(np.percentile(xs, q)), 1)

    return {"turns": turns, "head_start_ms": head_start_s * 1000, "calls_decoded_ahead": replayed,
            **{f"first_token_ms_{m}": {"p50": p(v, 50), "p95": p(v, 95), "each": [round(x) for x in v]}
               for m, v in first_token.items()}}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m robovoice.voice.speculate_eval",
                                     description="the shorter end-of-turn silence on recorded clips")
    parser.add_argument("cases", type=Path, nargs="*", help="audio case files (JSON lines with an 'audio' path)")
    parser.add_argument("--prefill-ab", action="store_true", help="the all-local bench with the prefill off, then on")
    parser.add_argument("--head-start-ms", type=float, default=None,
                        help="the model alone: first token without a prefill and with one started this much earlier "
                             "(-1: with one that has finished)")
    parser.add_argument("--turns", type=int, default=8, help="commands per --prefill-ab/--head-start-ms run")
    parser.add_argument("--early-ms", type=float, default=300.0, help="the shorter silence (default 300)")
    parser.add_argument("--full-ms", type=float, default=500.0, help="the full end-of-turn silence (default 500)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    args = parser.parse_args(argv)
    if args.head_start_ms is not None:
        print(json.dumps(asyncio.run(head_start(args.turns, args.head_start_ms / 1000))))
        return 0
    if args.prefill_ab:
        print(json.dumps(asyncio.run(prefill_ab(args.turns)), indent=1))
        return 0
    from robovoice.audio.stt import WhisperTranscriber

    stt = WhisperTranscriber()
    hint = asyncio.run(sim_hint("hey jarvis"))
    for cases in args.cases:
        report = measure(cases, stt, hint, args.early_ms / 1000, args.full_ms / 1000)
        summary = report.summary()
        if args.json:
            print(json.dumps({"cases": str(cases), **summary}))
            continue
        print(f"{cases}: {report.clips} clips; cut-offs full rule {report.cut_offs_full}, early rule "
              f"{report.cut_offs_early}; early ends {report.early_ends} (cutting: {report.early_ends_cutting})")
        print(f"  silence saved p50: ideal {summary['saved_ideal_ms']}, with measured STT "
              f"{summary['saved_measured_ms']}; STT at pauses {summary['stt_ms']}")
        print(f"  last pause judged incomplete: {report.incomplete}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
