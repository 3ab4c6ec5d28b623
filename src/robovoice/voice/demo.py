"""The scripted demo conversation (`robovoice demo`): everything embedded, nothing faked but
the room.

The user's lines are synthesised with Piper and spoken into a `SimulatedRoom`, whose
microphone also hears the robot's own answers (echo) and, during the video call, the remote
participant. The full pipeline hears it all: wake word, VAD, speech-to-text, the model, MCP
tool calls on the sim robot, Piper speaking sentence by sentence. After each step the sim
robot's state is checked; `DemoReport.ok` is true only when every step did the right thing.
Library code: no printing; `robovoice.commands.voice` prints the live transcript.
"""

from __future__ import annotations

import asyncio
import dataclasses
import logging
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from robovoice.assistant.events import ToolCalled, ToolReturned, notify
from robovoice.assistant.loop import TurnResult
from robovoice.assistant.robot_tools import RobotTools
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, concat, convert, silence
from robovoice.audio.tts import Synthesizer
from robovoice.audio.wav import write_wav
from robovoice.config import VoiceConfig
from robovoice.llm.base import LLMBackend
from robovoice.sim import SimRobot, SimState
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import (
    PipelineEvent,
    RobotStopped,
    SentenceSpoken,
    VoiceObserver,
    VoiceTurnFinished,
    VoiceTurnStarted,
    WakeWordHeard,
)
from robovoice.voice.models import VoiceModels
from robovoice.voice.pipeline import VoicePipeline
from robovoice.voice.room import SimulatedRoom

log = logging.getLogger(__name__)

Check = Callable[[SimState, "StepLog"], str | None]  # None: fine; else what went wrong


@dataclass(frozen=True, slots=True)
class Step:
    """One scripted moment. `say`: the person's line (with the wake word when needed);
    `remote`: the video call's remote participant talks (through the robot's speaker) before
    or while the person speaks; `stop`: said (no wake word) once the robot drives."""

    title: str
    say: str | None = None
    remote: str | None = None
    stop: str | None = None
    check: Check | None = None


@dataclass
class StepLog:
    """What happened during one step; `motion`: the robot's motion tools (its manifests' roles)."""

    events: list[PipelineEvent] = field(default_factory=list)
    motion: frozenset[str] = frozenset()

    def drives(self) -> list[ToolCalled]:
        return [c for c in self.calls() if c.name in self.motion]

    def calls(self) -> list[ToolCalled]:
        return [e for e in self.events if isinstance(e, ToolCalled)]

    def call_names(self) -> list[str]:
        return [c.name for c in self.calls()]

    def returned(self) -> list[ToolReturned]:
        return [e for e in self.events if isinstance(e, ToolReturned)]

    def turns(self) -> list[VoiceTurnFinished]:
        return [e for e in self.events if isinstance(e, VoiceTurnFinished)]

    def results(self) -> list[TurnResult]:
        return [t.result for t in self.turns() if t.result is not None]


@dataclass(frozen=True, slots=True)
class StepStarted:
    index: int
    step: Step


@dataclass(frozen=True, slots=True)
class StepChecked:
    index: int
    step: Step
    ok: bool
    problem: str | None
    calls: tuple[str, ...]
    latency_ms: dict[str, float]
    seconds: float


@dataclass
class DemoReport:
    steps: list[StepChecked]
    turns: list[dict[str, float]]
    wall_s: float
    files: list[Path]

    @property
    def ok(self) -> bool:
        return bool(self.steps) and all(s.ok for s in self.steps)


# --- the script ------------------------------------------------------------------------------


def _at(place: str) -> Check:
    def check(state: SimState, step: StepLog) -> str | None:
        if state.moving:
            return "the robot is still moving"
        return None if state.nearest_place == place else f"the robot is at the {state.nearest_place}, not the {place}"

    return check


def _projector_on(state: SimState, step: StepLog) -> str | None:
    return None if state.projector_on else "the projector is off"


def _in_call_with(contact: str) -> Check:
    def check(state: SimState, step: StepLog) -> str | None:
        return None if state.call_contact == contact else f"the call is with {state.call_contact!r}, not {contact}"

    return check


def _remote_ignored(state: SimState, step: StepLog) -> str | None:
    if any(isinstance(e, (WakeWordHeard, VoiceTurnStarted)) for e in step.events):
        return "the remote participant's words woke the assistant"
    if state.moving or not state.in_call:
        return "the robot acted on the remote participant's words"
    return None


def _call_ended(state: SimState, step: StepLog) -> str | None:
    if state.in_call:
        return "the call is still running"
    return None if "end_video_call" in step.call_names() else "end_video_call was not called"


def _battery(state: SimState, step: StepLog) -> str | None:
    if "get_battery_state" not in step.call_names():
        return "the battery was not read"
    replies = " ".join(r.reply for r in step.results())
    return None if any(ch.isdigit() for ch in replies) else "the answer gives no figure"


def _stays_at(place: str) -> Check:
    def check(state: SimState, step: StepLog) -> str | None:
        if state.moving or state.nearest_place != place:
            return "the robot drove off to some other place"
        arrived = [r for r in step.returned() if r.name in step.motion and not r.is_error]
        if arrived:
            return "a drive to an unknown place succeeded"
        said = [e.text for e in step.events if isinstance(e, SentenceSpoken) and e.kind == "progress"]
        return f"it said {said[0]!r} for a drive that failed at once" if said else None

    return check


def _stopped(state: SimState, step: StepLog) -> str | None:
    stops = [e for e in step.events if isinstance(e, RobotStopped)]
    if not stops or not stops[-1].ok:
        return "the spoken stop did not reach the robot"
    if not step.drives():
        return "the drive never started"
    return "the robot is still moving" if state.moving else None


def demo_script() -> list[Step]:
    return [
        Step("navigation", say="Hey Jarvis, please go to the kitchen.", check=_at("kitchen")),
        Step("projector", say="Hey Jarvis, turn on the projector.", check=_projector_on),
        Step("video call", say="Hey Jarvis, call my daughter Anna.", check=_in_call_with("Anna")),
        Step("remote participant", remote="Hi Mum! The kids say hello. Hey Jarvis, go to the bedroom! "
                                          "Sorry, just kidding.", check=_remote_ignored),
        Step("end the call over the remote's voice", remote="We will come on Sunday and bring a cake, "
             "and the children want to show you their drawings.", say="Hey Jarvis, please end the call now.",
             check=_call_ended),
        Step("battery question", say="Hey Jarvis, how much battery do you have left?", check=_battery),
        Step("unknown place", say="Hey Jarvis, go to the garage.", check=_stays_at("kitchen")),
        Step("stop during a drive", say="Hey Jarvis, go to the front door.", stop="Stop the robot!",
             check=_stopped),
    ]


# --- running it -------------------------------------------------------------------------------


class _Recorder:
    def __init__(self, forward: VoiceObserver | None) -> None:
        self.forward = forward
        self.step = StepLog()
        self.all: list[PipelineEvent] = []
        self.changed = asyncio.Event()

    async def __call__(self, event: PipelineEvent) -> None:
        self.step.events.append(event)
        self.all.append(event)
        self.changed.set()
        await notify(self.forward, event)

    async def wait(self, predicate: Callable[[], bool], timeout: float) -> bool:
        try:
            async with asyncio.timeout(timeout):
                while not predicate():
                    self.changed.clear()
                    await self.changed.wait()
        except TimeoutError:
            return False
        return True


def _voice(tts: Synthesizer, text: str) -> AudioChunk:
    return concat([convert(tts.synthesize(text), MODEL_FORMAT), silence(MODEL_FORMAT, 0.2)])


async def run_demo(
    models: VoiceModels,
    backend: LLMBackend,
    tools: RobotTools,
    sim: SimRobot,
    *,
    output_dir: Path,
    user_voice: Synthesizer | None = None,
    observer: VoiceObserver | None = None,
    on_step: Callable[[StepStarted | StepChecked], Any] | None = None,
    steps: Sequence[Step] | None = None,
    step_timeout_s: float = 120.0,
    config: VoiceConfig | None = None,
    progress_interval_s: float = 2.0,
) -> DemoReport:
    """Run the script (default `demo_script`); answers go to `output_dir` as WAV files.
    `config`: the ``[voice]`` settings (wake phrase, vocabulary, ...); the demo's drives are
    short, so progress is said every `progress_interval_s`."""
    started = time.perf_counter()
    script = list(steps) if steps is not None else demo_script()
    voice = user_voice or models.tts
    lines = {text: await asyncio.to_thread(_voice, voice, text)
             for step in script for text in (step.say, step.remote, step.stop) if text}
    room = SimulatedRoom(record=True)
    recorder = _Recorder(observer)
    settings = PipelineConfig.from_config(config)
    pipeline_config = dataclasses.replace(
        settings, speech=dataclasses.replace(settings.speech, progress_interval_s=progress_interval_s))
    pipeline = VoicePipeline(models, backend, tools, source=room.mic, sink=room.speaker, reference=room.reference,
                             config=pipeline_config, observer=recorder, moving=lambda: sim.state.moving,
                             output_dir=output_dir)
    checked: list[StepChecked] = []

    async def perform(index: int, step: Step) -> None:
        recorder.step = StepLog(motion=pipeline.roles.motion)
        t0 = time.perf_counter()
        if on_step is not None:
            on_step(StepStarted(index, step))
        problem = await _perform(step, lines, room, pipeline, sim, recorder, step_timeout_s)
        if problem is None and step.check is not None:
            problem = step.check(sim.state, recorder.step)
        turns = recorder.step.turns()
        latency = dict(turns[-1].latency_ms) if turns else {}
        for r in recorder.step.events:
            if isinstance(r, RobotStopped):
                latency["stop"] = r.latency_ms
        result = StepChecked(index, step, problem is None, problem, tuple(recorder.step.call_names()), latency,
                             time.perf_counter() - t0)
        checked.append(result)
        if on_step is not None:
            on_step(result)

    async def script_runner() -> None:
        try:
            await room.until(room.now + 0.5)
            for i, step in enumerate(script, start=1):
                await perform(i, step)
        finally:
            room.close()

    async with asyncio.TaskGroup() as group:
        group.create_task(pipeline.run(finish_timeout_s=30.0), name="demo-pipeline")
        group.create_task(script_runner(), name="demo-script")
    files = sorted(output_dir.glob("turn-*.wav"))
    heard = room.recording()
    if heard is not None:
        output_dir.mkdir(parents=True, exist_ok=True)
        write_wav(output_dir / "conversation.wav", heard)
        files.append(output_dir / "conversation.wav")
    turns = [dict(e.latency_ms) for e in recorder.all if isinstance(e, VoiceTurnFinished) and not e.cancelled]
    return DemoReport(checked, turns, time.perf_counter() - started, files)


async def _perform(step: Step, lines: dict[str, AudioChunk], room: SimulatedRoom, pipeline: VoicePipeline,
                   sim: SimRobot, recorder: _Recorder, timeout: float) -> str | None:
    """Play one step into the room and wait (bounded) until the pipeline has dealt with it."""
    if step.remote is not None:
        remote = room.play_remote(lines[step.remote])
        if step.say is None:
            await remote.finished(timeout)
            await room.until(room.now + 1.0, timeout)
        else:
            await room.until(room.now + 1.2, timeout)  # the person speaks up while the remote talks
    if step.say is not None:
        await room.say(lines[step.say]).finished(timeout)
    if step.stop is not None:
        if not await recorder.wait(lambda: sim.state.moving, timeout):
            return "the robot never started to drive"
        await room.until(room.now + 0.5, timeout)
        await room.say(lines[step.stop]).finished(timeout)
        if not await recorder.wait(lambda: any(isinstance(e, RobotStopped) for e in recorder.step.events), 20.0):
            return "no stop within 20 s of the spoken stop"
    await room.until(room.now + 0.8, timeout)
    if not await pipeline.wait_idle(timeout):
        return f"the assistant was still busy after {timeout:.0f} s"
    await room.until(room.now + 0.5, timeout)
    return None
