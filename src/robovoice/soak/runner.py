"""`run_soak`: the whole embedded assistant listening to hours of a home, in stream time.

The sim robot (over the real MCP client), the given model backend and the voice pipeline
with the given models hear a `SimulatedRoom` whose microphone runs in accelerated stream time
(`clock.StreamClock`). A script alternates stretches of background (television talk without
the wake phrase, music-like tones, pink noise, quiet) with spoken commands at random
intervals (`script.next_command`), each waited on (bounded) and judged from the robot's state.
Meanwhile `probe.take_sample` looks at the process every `sample_minutes` of stream time.
Counted: commands answered/done, false wakes (outside a command), actuating tool calls outside
a command, ERROR log records and exceptions nobody handled, tasks and threads left behind.
"""

from __future__ import annotations

import asyncio
import dataclasses
import logging
import math
import threading
import time
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.events import ToolCalled
from robovoice.config import RobotConfig
from robovoice.llm.base import LLMBackend, ToolSpec
from robovoice.sim import SimRobot
from robovoice.soak.clock import StreamClock
from robovoice.soak.probe import Sample, take_sample
from robovoice.soak.report import SoakReport, Tally
from robovoice.soak.script import Command, Outcome, judge, next_command
from robovoice.soak.sounds import SoakSounds
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import PipelineEvent, RobotStopped, SentenceSpoken, VoiceTurnStarted, WakeWordHeard
from robovoice.voice.models import VoiceModels
from robovoice.voice.pipeline import VoicePipeline
from robovoice.voice.room import SimulatedRoom

log = logging.getLogger(__name__)

BACKGROUND_KINDS = ("tv", "music", "pink", "quiet")
BACKGROUND_WEIGHTS = (0.45, 0.2, 0.2, 0.15)
NEVER = 1e9  # a bound for waits on stream time that the script itself ends
HANG_S = 900.0  # more than this after a command's first timeout: the turn hangs


@dataclass(frozen=True, slots=True)
class SoakSettings:
    """`hours` of stream time; commands every `mean_gap_minutes` on average (exponential, at
    least 20 s apart); a sample every `sample_minutes`; figures after `warm_up_minutes`.

    `sim_speed` 1: the robot drives at its real speed (0.5 m/s, a drive 9-24 s) while the
    assistant hears and answers in real time (the stream is paced while it works). A faster
    sim ends a drive before anyone could say "stop" into it (at 10 a drive lasted 1-2.4 s, less
    than the stop line, the end of speech and its transcription: 0/3 stops in the first run)
    and drains the battery ten times faster than the hours of the home being simulated."""

    hours: float = 2.0
    seed: int = 1
    mean_gap_minutes: float = 3.0
    sample_minutes: float = 5.0
    warm_up_minutes: float = 15.0
    sim_speed: float = 1.0
    turn_timeout_s: float = 180.0


@dataclass
class _Run:
    """The live state the script and the observer share."""

    room: SimulatedRoom
    pipeline: VoicePipeline
    sim: SimRobot
    tally: Tally
    actuating: frozenset[str]
    command: list[PipelineEvent] | None = None  # events of the command under way
    changed: asyncio.Event = field(default_factory=asyncio.Event)
    ending: asyncio.Event = field(default_factory=asyncio.Event)  # the run is asked to end (Ctrl-C)

    def observe(self, event: PipelineEvent) -> None:
        if self.command is not None:
            self.command.append(event)
            self.changed.set()
            return
        if isinstance(event, WakeWordHeard):
            self.tally.false_wakes += 1
        elif isinstance(event, VoiceTurnStarted):
            self.tally.turns_outside += 1
        elif isinstance(event, ToolCalled) and event.name in self.actuating:
            self.tally.unasked.append(event.name)

    async def wait_event(self, kind: type[Any], timeout: float) -> bool:
        try:
            async with asyncio.timeout(timeout):
                while not any(isinstance(e, kind) for e in self.command or ()):
                    self.changed.clear()
                    await self.changed.wait()
        except TimeoutError:
            return False
        return True


class _ErrorCounter(logging.Handler):
    def __init__(self, tally: Tally) -> None:
        super().__init__(logging.WARNING)
        self.tally = tally

    def emit(self, record: logging.LogRecord) -> None:
        if record.levelno >= logging.ERROR:
            self.tally.error_logs += 1
            if len(self.tally.first_errors) < 10:
                self.tally.first_errors.append(f"{record.name}: {record.getMessage()}"[:300])
        else:
            self.tally.warning_logs += 1


async def _give(run: _Run, cmd: Command, sounds: SoakSounds, timeout: float) -> Outcome:
    """Say `cmd` (and its follow-up), wait until the assistant is done with it, judge it."""
    room, pipeline, sim = run.room, run.pipeline, run.sim
    outcome = Outcome(cmd, room.now)
    events: list[PipelineEvent] = []
    run.command = events
    started = time.perf_counter()
    try:
        await room.say(sounds.command(cmd.say), gap_s=0.3).finished(timeout)
        if cmd.follow is not None and cmd.kind == "stop":
            # (a drive that never starts is waited for a minute, unless the run is asked to end)
            if await _wait(lambda: sim.state.moving or run.ending.is_set(), run, 60.0) and not run.ending.is_set():
                # said once the robot's own "On my way…" has ended: over it, Whisper tiny merges both
                # ("On my way, stop for the robot!", not a stop); a stop over the robot's voice is a
                # barge-in, which the soak gives apart
                await _wait(lambda: not pipeline.speech.busy, run, 30.0)
                await room.until(room.now + 0.5, timeout)
                await room.say(sounds.command(cmd.follow)).finished(timeout)
                await run.wait_event(RobotStopped, 20.0)
        elif cmd.follow is not None and await run.wait_event(SentenceSpoken, timeout):
            await room.say(sounds.command(cmd.follow)).finished(timeout)  # the barge-in
        await room.until(room.now + 0.8, timeout)
        if not await pipeline.wait_idle(timeout):
            # slow, not lost: keep the command's window open so its late calls are not counted as
            # unasked; a turn that never ends is a hang, reported as such
            outcome.late = True
            if not await pipeline.wait_idle(HANG_S):
                outcome.problem = f"still busy {timeout + HANG_S:.0f} s after the command (a hang)"
        await _wait(lambda: not sim.state.moving, run, 60.0)
        await room.until(room.now + 0.5, timeout)
    except TimeoutError:
        outcome.problem = "the room's stream stalled"
    finally:
        run.command = None
    if outcome.problem is None:
        judge(outcome, events, sim.state)
    outcome.wall_s = time.perf_counter() - started
    return outcome


async def _wait(predicate: Any, run: _Run, timeout: float) -> bool:
    try:
        async with asyncio.timeout(timeout):
            while not predicate():
                await asyncio.sleep(0.05)  # polling the sim's state, which has no event
    except TimeoutError:
        return False
    return True


async def _background(run: _Run, sounds: SoakSounds, rng: np.random.Generator, seconds: float,
                      ending: asyncio.Event) -> None:
    end = run.room.now + seconds
    while run.room.now < end - 1.0 and not ending.is_set():
        piece = min(end - run.room.now, float(rng.uniform(20.0, 90.0)))
        kind = str(rng.choice(BACKGROUND_KINDS, p=np.array(BACKGROUND_WEIGHTS) / sum(BACKGROUND_WEIGHTS)))
        if kind == "quiet":
            await run.room.until(run.room.now + piece, NEVER)
        else:
            await run.room.say(sounds.background(kind, piece)).finished(NEVER)
        run.room.played.clear()  # the room's own record of the robot's speech; not the assistant's memory


async def _script(run: _Run, settings: SoakSettings, sounds: SoakSounds, rng: np.random.Generator,
                  commands: Sequence[Command] | None, ending: asyncio.Event) -> None:
    end = settings.hours * 3600.0
    given = iter(commands) if commands is not None else None
    try:
        await run.room.until(run.room.now + 0.5, NEVER)
        while run.room.now < end and not ending.is_set():
            gap = max(20.0, float(rng.exponential(settings.mean_gap_minutes * 60.0)))
            await _background(run, sounds, rng, min(gap, end - run.room.now), ending)
            if run.room.now >= end or ending.is_set():
                break
            cmd = next_command(rng, run.sim.state) if given is None else next(given, None)
            if cmd is None:
                break  # the given commands are all said
            outcome = await _give(run, cmd, sounds, settings.turn_timeout_s)
            run.tally.outcomes.append(outcome)
            log.info("soak %.0f s (wall %.1f s): %s -> %s", outcome.sim_at, outcome.wall_s, outcome.command.say,
                     ("ok" if outcome.done else str(outcome.problem)) + (" (late)" if outcome.late else ""))
    finally:
        run.room.close()


async def _sampler(room: SimulatedRoom, samples: list[Sample], every_s: float, wall0: float, tally: Tally) -> None:
    t = 0.0
    while True:
        sample = take_sample(room.now, time.perf_counter() - wall0)
        samples.append(sample)
        log.info("soak sample %s; commands %d given, %d answered; false wakes %d; unasked %d; errors %d",
                 sample.to_dict(), len(tally.outcomes), sum(o.answered for o in tally.outcomes), tally.false_wakes,
                 len(tally.unasked), tally.error_logs)
        t += every_s
        await room.until(t, NEVER)


async def run_soak(models: VoiceModels, backend: LLMBackend, settings: SoakSettings = SoakSettings(), *,
                   warm_up: Callable[[Sequence[ToolSpec]], Awaitable[Any]] | None = None,
                   commands: Sequence[Command] | None = None, ending: asyncio.Event | None = None) -> SoakReport:
    """See the module docstring. `backend` is used, not closed; `warm_up` is given the robot's
    tools before the first sound (the embedded model evaluates its prompt prefix then).
    `commands`: these, in order (then the run ends), instead of the random script: a test
    gives the one scenario it looks at. `ending`: once set, the run ends early (after the
    command under way) and reports what it has, marked `ended_early`."""
    ending = ending or asyncio.Event()
    rng = np.random.default_rng(settings.seed)
    sounds = SoakSounds(models.tts, rng)
    tally = Tally()
    counter = _ErrorCounter(tally)
    logging.getLogger().addHandler(counter)
    loop = asyncio.get_running_loop()
    previous_handler = loop.get_exception_handler()

    def unhandled(_loop: asyncio.AbstractEventLoop, context: dict[str, Any]) -> None:
        tally.unhandled.append(str(context.get("exception") or context.get("message"))[:300])

    loop.set_exception_handler(unhandled)
    wall0 = time.perf_counter()
    samples: list[Sample] = []
    try:
        async with connect_robot(RobotConfig(address=f"sim://?speed={settings.sim_speed:g}")) as link:
            sim = link.sim
            assert sim is not None, "sim:// always runs the sim here"
            specs = await link.tools.specs()
            actuating = frozenset(s.name for s in specs if not s.read_only)
            if warm_up is not None:
                await warm_up(specs)
            room = SimulatedRoom(speed=math.inf)
            source = StreamClock(room.mic)
            base = PipelineConfig.from_config()
            config = dataclasses.replace(base, speech=dataclasses.replace(base.speech, progress_interval_s=4.0))

            def observe(event: PipelineEvent) -> None:
                run.observe(event)  # `run` is bound below, before the pipeline starts

            pipeline = VoicePipeline(models, backend, link.tools, source=source, sink=room.speaker,
                                     reference=room.reference, config=config, observer=observe,
                                     moving=lambda: sim.state.moving)
            source.busy = lambda: not pipeline.floor.idle or pipeline.speech.busy or sim.state.moving
            run = _Run(room, pipeline, sim, tally, actuating, ending=ending)
            tally.tasks_before, threads_before = len(asyncio.all_tasks()), {t.name for t in threading.enumerate()}
            try:
                async with asyncio.TaskGroup() as group:
                    group.create_task(pipeline.run(finish_timeout_s=30.0), name="soak-pipeline")
                    sampler = group.create_task(_sampler(room, samples, settings.sample_minutes * 60.0, wall0, tally),
                                                name="soak-sampler")
                    await _script(run, settings, sounds, rng, commands, ending)
                    sampler.cancel()
            except Exception as exc:  # the report says the run crashed, with what
                log.exception("the soak run failed")
                tally.unhandled.append(f"{type(exc).__name__}: {exc}"[:300])
            await asyncio.sleep(0)
            samples.append(take_sample(room.now, time.perf_counter() - wall0))
            tally.tasks_after = len(asyncio.all_tasks())
            tally.threads_before = len(threads_before)
            threads_after = {t.name for t in threading.enumerate()}
            tally.threads_after, tally.threads_new = len(threads_after), sorted(threads_after - threads_before)
            tally.paced_s, tally.free_s = source.paced_s, source.free_s
            tally.sim_s = room.now
    finally:
        loop.set_exception_handler(previous_handler)
        logging.getLogger().removeHandler(counter)
    return SoakReport.build({**settings_dict(settings), "ended_early": ending.is_set()}, tally, samples,
                            time.perf_counter() - wall0,
                            settings.warm_up_minutes * 60.0, tv_voice=sounds.tv_voice)


def settings_dict(settings: SoakSettings) -> dict[str, Any]:
    return dataclasses.asdict(settings)
