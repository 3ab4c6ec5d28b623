"""The spoken stop's latency (issue 12: "a spoken stop reaches the robot <= 0.5 s after the
last word"): the shipped voice models hearing stop clips, said without the wake word while
the sim robot drives, in a real-time `SimulatedRoom`.

Each stop: the sim starts a long drive (``apply_setup("driving")``), the person says one
clip, and the pipeline's stop path (stop check: speech-to-text with the stop hint, the stop
grammar, the robot's stop tool over MCP; no language model) stops the robot. Two figures per
stop, from the user's last word (`RobotStopped.from_last_word_ms`, the pipeline's stream
clock mapped to the wall clock):

- ``stop_sent``: the stop tool's call leaving the pipeline for the robot (timed by a wrapper
  around the robot's tools: the sim receives it over in-process MCP right after);
- ``stop_answered``: the stop tool's answer (the sim has halted the drive by then).

When the stop check began (``decided``) is given too: at the first pause after the stop, once
its speculative transcript is a stop (`StopController.check_pause`), else at the end-of-turn
decision; what waiting for silence costs.

    python -m robovoice.voice.bench stops --turns 12
    robovoice bench voice stops --turns 12
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from robovoice.assistant.robot_tools import ProgressCallback, Toolbox, ToolOutcome
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, concat, convert
from robovoice.audio.format import silence as make_silence
from robovoice.audio.wav import read_wav
from robovoice.config import VoiceConfig
from robovoice.llm.base import ToolSpec
from robovoice.manifest.voice import VoiceDecl
from robovoice.voice.events import PipelineEvent, RobotStopped, UtteranceIgnored
from robovoice.voice.models import VoiceModels

log = logging.getLogger(__name__)

#: Stop phrases synthesised with Piper, said without the wake word.
STOP_PHRASES = ("Stop!", "Stop the robot.", "Halt!", "Stop moving!", "Stop right there.", "Freeze!")


class TimedTools:
    """The robot's tools, each call's start and end (perf_counter) noted by tool name."""

    def __init__(self, tools: Toolbox) -> None:
        self._tools = tools
        self.calls: list[tuple[str, float, float]] = []

    async def specs(self) -> list[ToolSpec]:
        return await self._tools.specs()

    async def call(self, name: str, arguments: dict[str, Any], on_progress: ProgressCallback | None = None
                   ) -> ToolOutcome:
        sent = time.perf_counter()
        try:
            return await self._tools.call(name, arguments, on_progress)
        finally:
            self.calls.append((name, sent, time.perf_counter()))

    def voice(self) -> Mapping[str, VoiceDecl]:
        return self._tools.voice()


def stop_clips(models: VoiceModels, wavs: Sequence[Path] = ()) -> list[tuple[str, AudioChunk]]:
    """(name, audio) of each stop clip: `wavs` when given, else `STOP_PHRASES` spoken by Piper
    (with 0.1 s of silence after, as a recorded clip has)."""
    if wavs:
        return [(p.name, read_wav(p)) for p in wavs]
    return [(text, concat([convert(models.tts.synthesize(text), MODEL_FORMAT), make_silence(MODEL_FORMAT, 0.1)]))
            for text in STOP_PHRASES]


async def bench_stops(turns: int = 12, *, models: VoiceModels | None = None, wavs: Sequence[Path] = (),
                      voice: VoiceConfig | None = None) -> dict[str, Any]:
    """`turns` spoken stops (the clips in turn) while the sim robot drives; ms from the last word."""
    from robovoice.assistant.connect import connect_robot
    from robovoice.config import RobotConfig
    from robovoice.voice.bench import _figures, _InstantBackend, machine
    from robovoice.voice.config import PipelineConfig
    from robovoice.voice.models import load_voice_models
    from robovoice.voice.pipeline import VoicePipeline
    from robovoice.voice.room import SimulatedRoom

    if models is None:
        models = await asyncio.to_thread(load_voice_models)
    clips = stop_clips(models, wavs)
    stopped: list[tuple[RobotStopped, float]] = []  # with the perf_counter time it was seen
    ignored: list[UtteranceIgnored] = []
    seen = asyncio.Event()

    def observe(event: PipelineEvent) -> None:
        if isinstance(event, RobotStopped):
            stopped.append((event, time.perf_counter()))
            seen.set()
        elif isinstance(event, UtteranceIgnored):
            ignored.append(event)
            seen.set()

    per_stop: list[dict[str, Any]] = []
    # real time: the drive is long enough for a stop said into it, and stream time is wall time
    async with connect_robot(RobotConfig(address="sim://")) as link:
        sim = link.sim
        assert sim is not None
        tools = TimedTools(link.tools)
        room = SimulatedRoom()
        # the stop path uses no language model: an instant one stands in for it
        pipeline = VoicePipeline(models, _InstantBackend(), tools, source=room.mic, sink=room.speaker,
                                 reference=room.reference, observer=observe, moving=lambda: sim.state.moving,
                                 config=PipelineConfig.from_config(voice))

        async def say_stops() -> None:
            try:
                await room.until(room.now + 0.5)
                for i in range(turns):
                    name, clip = clips[i % len(clips)]
                    await sim.apply_setup("driving")
                    await room.until(room.now + 0.5)
                    seen.clear()
                    before, calls = len(stopped), len(tools.calls)
                    await room.say(clip, gap_s=0.3).finished(60.0)
                    try:
                        async with asyncio.timeout(120.0):
                            await seen.wait()
                    except TimeoutError:
                        log.warning("stop %d (%s): nothing heard within 120 s", i, name)
                    await pipeline.wait_idle(120.0)
                    await room.until(room.now + 1.0)  # the reply's echo is over before the next drive
                    per_stop.append(_one(name, stopped[before:], tools.calls[calls:], pipeline.stopper.roles.stop,
                                         halted=not sim.state.moving))
            finally:
                room.close()

        started = time.perf_counter()
        async with asyncio.TaskGroup() as group:
            group.create_task(pipeline.run(finish_timeout_s=30.0))
            group.create_task(say_stops())
        wall = time.perf_counter() - started

    def column(key: str) -> list[float]:
        return [s[key] for s in per_stop if s.get(key) is not None]

    return {
        "what": "spoken stops (no wake word) while the sim robot drives, shipped voice models, real-time room; "
                "ms from the user's last word to the stop call sent to the robot / answered (robot halted)",
        "stops": turns,
        "stopped": sum(1 for s in per_stop if s["ok"]),
        "from_last_word_ms": {"stop_sent": _figures(column("stop_sent")),
                              "stop_answered": _figures(column("stop_answered")),
                              "decided": _figures(column("decided"))},
        "missed": [s["clip"] for s in per_stop if not s["ok"]],
        # every utterance that was no stop, and why (the robot's own reply: own_voice)
        "ignored": [{"reason": e.reason, "text": e.text} for e in ignored],
        "per_stop": per_stop,
        "wall_s": round(wall, 1),
        "machine": machine(),
    }


def _one(name: str, stopped: Sequence[tuple[RobotStopped, float]], calls: Sequence[tuple[str, float, float]],
         tool: str | None, *, halted: bool) -> dict[str, Any]:
    """One stop's figures: the first `RobotStopped` after the clip and its stop tool call;
    `halted`: the sim no longer moves."""
    if not stopped:
        return {"clip": name, "ok": False}
    event, _ = stopped[0]
    out: dict[str, Any] = {"clip": name, "ok": event.ok and halted, "stop_answered": event.from_last_word_ms,
                           "decided": None, "stop_sent": None}
    if event.from_last_word_ms is None:
        return out
    out["decided"] = round(event.from_last_word_ms - event.latency_ms, 1)
    mine = [c for c in calls if c[0] == tool]
    if mine:
        _, sent, answered = mine[0]
        out["stop_sent"] = round(event.from_last_word_ms - (answered - sent) * 1000.0, 1)
    return out
