"""Benchmarks of the voice pipeline (DESIGN.md §7), figures for docs/performance.md.

- `bench_local`: the all-local stack (openWakeWord, Silero, Moonshine, the embedded
  Qwen2.5-Coder-1.5B, MCP tool calls on the sim robot, Piper) hearing 22 spoken commands
  (synthesised with Piper, played into a `SimulatedRoom` in real time). Every stage is given
  from two origins: the user's last word (the VAD's last voiced frame, issue 12:
  ``speech_end_to_first_audio``) and the end-of-turn decision, which comes after the
  end-of-turn silence. After each turn, the *naive chain* of the same models in the same
  process on the same clip, for comparison: speech-to-text of the whole clip once the full
  end-of-turn silence has passed, the assistant's whole turn, speech synthesis of the whole
  reply (no streaming, no speculation); and the ratio of the two.
- `bench_overhead`: the pipeline's own cost per turn with every model replaced by an
  instant fake (so end of speech -> first audio *is* the overhead: framing, queues, tasks,
  executors, the assistant loop, the speech queue), plus the front end's CPU per second of
  audio.

- `bench_stops.bench_stops`: spoken stops while the sim robot drives, from the last word to
  the robot (issue 12's 0.5 s).

    python -m robovoice.voice.bench overhead --turns 30
    python -m robovoice.voice.bench local --turns 22
    python -m robovoice.voice.bench stops --turns 12

(The same as ``robovoice bench voice overhead|local|stops --json``.)
"""

from __future__ import annotations

import argparse
import asyncio
import functools
import json
import logging
import math
import os
import platform
import time
from collections.abc import AsyncGenerator, Awaitable, Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from robovoice.assistant.loop import Assistant
from robovoice.assistant.metrics import percentile
from robovoice.assistant.robot_tools import ProgressCallback, RobotTools, ToolOutcome
from robovoice.audio.fakes import EnergyVAD, ToneSynthesizer, ToneWakeDetector
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, concat, convert, float32_to_int16
from robovoice.audio.format import silence as make_silence
from robovoice.audio.stt import Transcript
from robovoice.config import VoiceConfig
from robovoice.llm.base import ChatMessage, Finished, LLMEvent, TextDelta, ToolSpec
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import PipelineEvent, VoiceTurnFinished, VoiceTurnStarted
from robovoice.voice.models import VoiceModels
from robovoice.voice.pipeline import VoicePipeline
from robovoice.voice.room import SimulatedRoom
from robovoice.voice.utterance import strip_wake_words

log = logging.getLogger(__name__)

STAGES = ("endpoint", "transcript", "first_token", "tool_call", "tool_result", "first_sentence", "first_audio")

#: Commands for the all-local benchmark, in an order the robot can follow (a call before its
#: hang-up): drives, the projector, calls, battery and pose questions, small talk.
LOCAL_COMMANDS = (
    "Hey Jarvis, turn on the projector.",
    "Hey Jarvis, how much battery do you have left?",
    "Hey Jarvis, go to the kitchen.",
    "Hey Jarvis, good morning!",
    "Hey Jarvis, where are you right now?",
    "Hey Jarvis, switch the projector off.",
    "Hey Jarvis, call Anna.",
    "Hey Jarvis, end the call.",
    "Hey Jarvis, drive to the living room.",
    "Hey Jarvis, what can you do?",
    "Hey Jarvis, is the projector on?",
    "Hey Jarvis, go to the bedroom, please.",
    "Hey Jarvis, are you charging at the moment?",
    "Hey Jarvis, call my son.",
    "Hey Jarvis, hang up, please.",
    "Hey Jarvis, thank you.",
    "Hey Jarvis, come to the front door.",
    "Hey Jarvis, which room are you in?",
    "Hey Jarvis, who can you call?",
    "Hey Jarvis, go to the bathroom.",
    "Hey Jarvis, how are you today?",
    "Hey Jarvis, go back to your charging dock.",
)


@dataclass(frozen=True, slots=True)
class StageFigures:
    p50: float
    p95: float
    n: int


def stage_table(turns: Sequence[dict[str, float]]) -> dict[str, StageFigures]:
    """p50/p95 per stage (``tool_call:<name>`` folded into ``tool_call``)."""
    values: dict[str, list[float]] = {}
    for marks in turns:
        folded: dict[str, float] = {}
        for stage, ms in marks.items():
            key = stage.split(":", 1)[0]
            folded[key] = min(ms, folded.get(key, math.inf))
        for stage, ms in folded.items():
            values.setdefault(stage, []).append(ms)
    return {s: StageFigures(round(percentile(v, 50), 1), round(percentile(v, 95), 1), len(v))
            for s, v in sorted(values.items())}


def machine() -> dict[str, Any]:
    load = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    return {"cpus": os.cpu_count(), "python": platform.python_version(), "load_avg_1_5_15": [round(x, 2) for x in load]}


# --- instant fakes for the overhead measurement -----------------------------------------------------


class _InstantStt:
    def transcribe(self, audio: AudioChunk, hint: str = "") -> Transcript:
        return Transcript("Hey Jarvis, say something.", audio.duration_s)


class _InstantBackend:
    """An in-process model that answers at once with one sentence."""

    name = "instant"
    accepts_audio = False

    async def stream(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]
    ) -> AsyncGenerator[LLMEvent, None]:
        yield TextDelta("Okay, done.")
        yield Finished("stop")

    async def aclose(self) -> None:
        return None


class _NoTools(RobotTools):
    """A robot without tools (the overhead run needs no MCP)."""

    _none: list[ToolSpec] = []  # noqa: RUF012 (one list: the pipeline sees an unchanged tool list)

    async def specs(self) -> list[ToolSpec]:
        return self._none

    async def call(self, name: str, arguments: dict[str, Any], on_progress: ProgressCallback | None = None
                   ) -> ToolOutcome:
        return ToolOutcome("{}", False, 0.0)


def _tone_command(seconds: float = 1.0) -> AudioChunk:
    rng = np.random.default_rng(7)
    n_tone, n_talk = round(0.5 * MODEL_FORMAT.rate), round(seconds * MODEL_FORMAT.rate)
    t = np.arange(n_tone) / MODEL_FORMAT.rate
    tone = 0.14 * np.sin(2 * np.pi * 1000 * t)
    talk = rng.standard_normal(n_talk) * 0.1 * (0.6 + 0.4 * np.sin(2 * np.pi * 4 * np.arange(n_talk) / 16000))
    return AudioChunk(float32_to_int16(np.concatenate([tone, talk]).astype(np.float32)), MODEL_FORMAT)


async def _run_turns(pipeline: VoicePipeline, room: SimulatedRoom, commands: Sequence[AudioChunk],
                     finished: list[VoiceTurnFinished], *, reset: bool, timeout: float,
                     after: Callable[[AudioChunk], Awaitable[None]] | None = None) -> None:
    """Say each command once the pipeline is idle; `after(command)` runs after each turn."""
    try:
        await room.until(room.now + 0.5)
        for audio in commands:
            if reset:
                pipeline.assistant.reset()  # every turn from a fresh conversation
            await room.say(audio, gap_s=0.3).finished(timeout)
            await room.until(room.now + 0.8, timeout)
            if not await pipeline.wait_idle(timeout):
                log.warning("a benchmark turn did not finish within %.0f s", timeout)
            if after is not None:
                await after(audio)
    finally:
        room.close()


async def bench_overhead(turns: int = 30, *, speed: float = 4.0) -> dict[str, Any]:
    """End of speech -> first audio with instant models: the pipeline's own time per turn."""
    models = VoiceModels(wake=ToneWakeDetector(), vad=EnergyVAD(), stt=_InstantStt(), tts=ToneSynthesizer(0.01),
                         playback_wake=ToneWakeDetector())
    room = SimulatedRoom(speed=speed)
    finished: list[VoiceTurnFinished] = []

    def observe(event: PipelineEvent) -> None:
        if isinstance(event, VoiceTurnFinished) and not event.cancelled:
            finished.append(event)

    pipeline = VoicePipeline(models, _InstantBackend(), _NoTools(), source=room.mic, sink=room.speaker,
                             reference=room.reference, observer=observe, moving=lambda: False)
    command = _tone_command()
    async with asyncio.TaskGroup() as group:
        group.create_task(pipeline.run(finish_timeout_s=10.0))
        group.create_task(_run_turns(pipeline, room, [command] * turns, finished, reset=True, timeout=30.0))
    marks = [dict(f.latency_ms) for f in finished]
    first_audio = [m["first_audio"] for m in marks if "first_audio" in m]
    return {
        "what": "end of speech -> first audio out with instant fake models (= pipeline overhead per turn)",
        "turns": len(finished),
        "first_audio_ms": {"p50": round(percentile(first_audio, 50), 2), "p95": round(percentile(first_audio, 95), 2),
                           "max": round(max(first_audio), 2)} if first_audio else None,
        "stages": {k: {"p50": v.p50, "p95": v.p95, "n": v.n} for k, v in stage_table(marks).items()},
        "frontend_ms_per_audio_s": round(1000 * pipeline.stats.frontend_s / max(pipeline.stats.audio_s, 1e-9), 2),
        "frontend_cpu_percent": round(100 * pipeline.stats.frontend_cpu_s / max(pipeline.stats.audio_s, 1e-9), 2),
        "machine": machine(),
    }


def _figures(values: Sequence[float]) -> dict[str, float] | None:
    if not values:
        return None
    return {"p50": round(percentile(values, 50), 1), "p95": round(percentile(values, 95), 1),
            "max": round(max(values), 1), "n": len(values)}


def _table(turns: Sequence[dict[str, float]]) -> dict[str, dict[str, float]]:
    return {k: {"p50": v.p50, "p95": v.p95, "n": v.n} for k, v in stage_table(turns).items()}


async def naive_turn(models: VoiceModels, assistant: Assistant, clip: AudioChunk, *,
                     end_silence_s: float, wake_phrase: str, hint: str) -> dict[str, float]:
    """The plain chain of the same models on one clip, in ms from the last word: the full
    end-of-turn silence (a wait, so its configured length is added, not slept), speech-to-text
    of the whole clip, the assistant's whole turn, speech synthesis of the whole reply.
    Nothing overlaps, nothing is streamed or speculated."""
    assert models.stt is not None
    assistant.reset()
    started = time.perf_counter()
    heard = await asyncio.to_thread(models.stt.transcribe, clip, hint)
    transcribed = time.perf_counter()
    result = await assistant.turn(strip_wake_words(heard.text, wake_phrase))
    answered = time.perf_counter()
    await asyncio.to_thread(models.tts.synthesize, result.reply or "Okay.")
    spoken = time.perf_counter()
    wait_ms = end_silence_s * 1000.0
    log.info("naive chain %r: first audio %.0f ms from the last word", heard.text, wait_ms + (spoken - started) * 1000)
    return {"endpoint": round(wait_ms, 1), "transcript": round(wait_ms + (transcribed - started) * 1000, 1),
            "reply": round(wait_ms + (answered - started) * 1000, 1),
            "first_audio": round(wait_ms + (spoken - started) * 1000, 1)}


async def bench_local(turns: int = len(LOCAL_COMMANDS), *, models: VoiceModels | None = None,
                      sim_speed: float = 10.0, commands: Sequence[str] = LOCAL_COMMANDS,
                      naive: bool = True, voice: VoiceConfig | None = None, checks: bool = True) -> dict[str, Any]:
    """The all-local stack, from spoken commands to first audio out, per stage, from the last
    word and from the end-of-turn decision; then the naive chain on the same clips. `voice`:
    the ``[voice]`` settings (default: their defaults); `checks`: False runs the pipeline's
    assistant without the check before acting (`Assistant(checks=False)`), the baseline of
    issue 11's latency bar."""
    from robovoice.assistant.connect import connect_robot
    from robovoice.assistant.prompt import SYSTEM_PROMPT
    from robovoice.config import RobotConfig
    from robovoice.llm.local import LocalLlamaBackend
    from robovoice.voice.models import load_voice_models

    if models is None:
        models = await asyncio.to_thread(load_voice_models, wake_phases=(voice or VoiceConfig()).wake_phases)
    said = [commands[i % len(commands)] for i in range(turns)]
    audio = {text: concat([convert(models.tts.synthesize(text), MODEL_FORMAT), make_silence(MODEL_FORMAT, 0.1)])
             for text in set(said)}
    finished: list[VoiceTurnFinished] = []
    heard: dict[int, str] = {}  # turn -> its transcript

    def observe(event: PipelineEvent) -> None:
        if isinstance(event, VoiceTurnFinished) and not event.cancelled:
            finished.append(event)
            spoken = event.result.metrics.from_speech_end() if event.result is not None else {}
            log.info("turn %d (%r): first audio %s ms from the last word", event.turn, heard.get(event.turn),
                     spoken.get("first_audio"))
        elif isinstance(event, VoiceTurnStarted):
            heard[event.turn] = event.text

    local = LocalLlamaBackend()
    robot = RobotConfig(address=f"sim://?speed={sim_speed:g}")
    naive_turns: list[dict[str, float]] = []
    try:
        # the naive chain has its own robot, so each command finds both robots in the same state;
        # its turns alternate with the pipeline's, so both see the same load from other jobs
        async with connect_robot(robot) as link, connect_robot(robot) as naive_link:
            await local.warm_up(SYSTEM_PROMPT, await link.tools.specs())
            sim = link.sim
            room = SimulatedRoom()  # real time: stream time and the wall clock advance together
            pipeline = VoicePipeline(models, local, link.tools, source=room.mic, sink=room.speaker,
                                     reference=room.reference, observer=observe,
                                     moving=(lambda: sim.state.moving) if sim is not None else None,
                                     config=PipelineConfig.from_config(voice),
                                     assistant=functools.partial(Assistant, checks=checks))
            naive_assistant = Assistant(local, naive_link.tools)

            async def naive_after(clip: AudioChunk) -> None:
                cfg = pipeline.config
                naive_turns.append(await naive_turn(models, naive_assistant, clip, hint=pipeline.hint,
                                                    end_silence_s=cfg.endpointer.end_silence_s,
                                                    wake_phrase=cfg.wake_phrase))

            started = time.perf_counter()
            async with asyncio.TaskGroup() as group:
                group.create_task(pipeline.run(finish_timeout_s=60.0))
                group.create_task(_run_turns(pipeline, room, [audio[t] for t in said], finished, reset=True,
                                             timeout=180.0, after=naive_after if naive else None))
            wall = time.perf_counter() - started
    finally:
        await local.aclose()
    from_decision = [dict(f.latency_ms) for f in finished]
    from_last_word = [f.result.metrics.from_speech_end() if f.result else {} for f in finished]
    first = [m["first_audio"] for m in from_last_word if "first_audio" in m]
    naive_first = [m["first_audio"] for m in naive_turns]
    out: dict[str, Any] = {
        "what": f"all-local stack, {len(said)} spoken commands; ms from the user's last word (the VAD's last voiced "
                "frame) and from the end-of-turn decision; naive chain of the same models for comparison",
        "commands": len(said),
        "checks": checks,
        "turns": len(finished),
        "speech_end_to_first_audio_ms": _figures(first),
        "stages_from_speech_end": _table(from_last_word),
        "stages_from_end_of_turn_decision": _table(from_decision),
        "per_turn": [{"heard": heard.get(f.turn, ""), "reply": f.result.reply if f.result else "",
                      "from_speech_end": spoken, "from_end_of_turn_decision": decided}
                     for f, spoken, decided in zip(finished, from_last_word, from_decision, strict=True)],
        "wall_s": round(wall, 1),
        "frontend_ms_per_audio_s": round(1000 * pipeline.stats.frontend_s / max(pipeline.stats.audio_s, 1e-9), 2),
        "frontend_cpu_percent": round(100 * pipeline.stats.frontend_cpu_s / max(pipeline.stats.audio_s, 1e-9), 2),
        "machine": machine(),
    }
    if naive:
        naive_fig = _figures(naive_first)
        out["naive_chain"] = {"speech_end_to_first_audio_ms": naive_fig, "stages_from_speech_end": _table(naive_turns)}
        pipe_fig = out["speech_end_to_first_audio_ms"]
        if naive_fig and pipe_fig:
            out["naive_over_pipeline"] = {q: round(naive_fig[q] / pipe_fig[q], 2) for q in ("p50", "p95")}
    return out


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m robovoice.voice.bench", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("which", choices=["overhead", "local", "stops"])
    parser.add_argument("--turns", type=int, default=None)
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.WARNING)
    if args.which == "overhead":
        result = asyncio.run(bench_overhead(args.turns or 30))
    elif args.which == "stops":
        from robovoice.voice.bench_stops import bench_stops

        result = asyncio.run(bench_stops(args.turns or 12))
    else:
        result = asyncio.run(bench_local(args.turns or len(LOCAL_COMMANDS)))
    print(json.dumps(result, indent=1))  # the module's command-line entry point prints its result
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
