"""Audio-device faults (issue 14): the microphone ends mid-turn, raises, stalls, or
disappears and comes back. The real pipeline (model fakes keyed to the test audio: tone =
wake word, noise = speech, a settable transcript), the sim robot over MCP, the fake vLLM
server routing by keywords; sources are a real `WavSource` or a scripted microphone that
fails on cue. With `GuardedSource` + `DeviceReaction` the robot ends up stopped (or where it
was sent), the user hears a short explanation, and the run recovers or ends cleanly with a
message; without the guard, the pipeline's error is the source's."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager
from dataclasses import dataclass
from pathlib import Path

import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.events import ToolCalled
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat, silence
from robovoice.audio.streams import AudioSource
from robovoice.audio.wav import MemorySink, WavSource, write_wav
from robovoice.config import RobotConfig
from robovoice.errors import AudioError
from robovoice.llm.fake_server import CallbackReply, FakeOpenAIServer
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.sim import SimRobot
from robovoice.voice.device import (
    BACK_MESSAGE,
    GONE_MESSAGE,
    LOST_MESSAGE,
    DeviceBack,
    DeviceGone,
    DeviceLost,
    DeviceReaction,
    GuardedSource,
)
from robovoice.voice.events import SentenceSpoken, VoiceTurnFinished
from robovoice.voice.pipeline import VoicePipeline

from ..voice.voice_kit import EventLog, SettableTranscriber, fake_models, join, keyword_router, wake_command

pytestmark = [pytest.mark.integration, pytest.mark.timeout(120)]

CHUNK_S = 0.08


class ScriptedMic:
    """A microphone in a test: `audio` in 80 ms chunks at `speed` x real time, then silence
    until `until()` holds, then `then`: ``end`` (the stream ends), ``fail`` (raises
    `AudioError`, as PortAudio does when a device is unplugged) or ``hang`` (nothing more)."""

    def __init__(self, audio: AudioChunk, then: str, until: Callable[[], bool] = lambda: True,
                 speed: float = 4.0) -> None:
        self.audio, self.then, self.until, self.speed = audio, then, until, speed
        self.closed = False

    @property
    def format(self) -> AudioFormat:
        return MODEL_FORMAT

    def __aiter__(self) -> AsyncIterator[AudioChunk]:
        return self._chunks()

    async def _chunks(self) -> AsyncIterator[AudioChunk]:
        n = round(CHUNK_S * MODEL_FORMAT.rate)
        samples = self.audio.samples
        t = 0.0
        for i in range(0, len(samples), n):
            await asyncio.sleep(CHUNK_S / self.speed)
            yield AudioChunk(samples[i:i + n], MODEL_FORMAT, t)
            t += CHUNK_S
        while not self.until() and not self.closed:
            await asyncio.sleep(CHUNK_S / self.speed)
            yield silence(MODEL_FORMAT, CHUNK_S, t)
            t += CHUNK_S
        if self.then == "fail":
            raise AudioError("PortAudio: device unavailable (the microphone was unplugged)")
        if self.then == "hang":
            await asyncio.Event().wait()

    async def aclose(self) -> None:
        self.closed = True


def plan(*items: AudioSource | Exception) -> Callable[[], AudioSource]:
    """A source factory: each call opens the next source (or raises the next error); past
    the end, the device is not there."""
    queue = list(items)

    def open_source() -> AudioSource:
        item = queue.pop(0) if queue else AudioError("no such audio device")
        if isinstance(item, Exception):
            raise item
        return item

    return open_source


@dataclass
class Rig:
    sim: SimRobot
    stt: SettableTranscriber
    log: EventLog
    sink: MemorySink
    pipeline: VoicePipeline

    def spoken(self) -> list[str]:
        return [e.text for e in self.log.of(SentenceSpoken)]

    async def run(self, timeout: float = 60.0) -> None:
        async with asyncio.timeout(timeout):
            await self.pipeline.run(finish_timeout_s=20.0)


@asynccontextmanager
async def rig(source: AudioSource | Callable[[SimRobot], AudioSource], sim_speed: float) -> AsyncIterator[Rig]:
    async with FakeOpenAIServer() as server, connect_robot(RobotConfig(address=f"sim://?speed={sim_speed:g}")) as link:
        server.default = CallbackReply(keyword_router)
        backend = OpenAICompatBackend(server.base_url, server.model)
        sim = link.sim
        assert sim is not None
        stt = SettableTranscriber()
        log, sink = EventLog(), MemorySink()
        mic = source(sim) if callable(source) else source
        pipeline = VoicePipeline(fake_models(stt), backend, link.tools, source=mic, sink=sink, observer=log,
                                 moving=lambda: sim.state.moving)
        try:
            yield Rig(sim, stt, log, sink, pipeline)
        finally:
            await backend.aclose()


def command(after_s: float = 0.3, tail_s: float = 0.9) -> AudioChunk:
    return join(silence(MODEL_FORMAT, after_s), wake_command(1.0), silence(MODEL_FORMAT, tail_s))


async def test_a_wav_that_ends_mid_turn_lets_the_turn_finish(tmp_path: Path) -> None:
    wav = tmp_path / "mic.wav"
    write_wav(wav, command())  # ends 0.9 s after the command: the drive has not even started
    guard = GuardedSource(lambda: WavSource(wav))
    async with rig(guard, sim_speed=20.0) as r:
        r.stt.text = "go to the kitchen"
        await r.run()
        state = r.sim.state
    assert not state.moving and state.nearest_place == "kitchen"
    finished = r.log.of(VoiceTurnFinished)
    assert len(finished) == 1 and not finished[0].cancelled and finished[0].result is not None
    assert finished[0].result.reply == "I am in the kitchen now."  # the drive's success phrase
    assert guard.events == [] and guard.failure is None  # a file that ends is not a fault


async def test_the_device_fails_mid_drive_and_never_returns() -> None:
    holder: list[GuardedSource] = []

    def make(sim: SimRobot) -> AudioSource:
        guard = GuardedSource(plan(ScriptedMic(command(), "fail", until=lambda: sim.state.moving)),
                              retry_s=0.1, give_up_s=0.6)
        holder.append(guard)
        return guard

    async with rig(make, sim_speed=1.0) as r:
        guard = holder[0]
        reaction = DeviceReaction(r.pipeline)
        guard.on_event = reaction
        r.stt.text = "go to the front door"
        await r.run()  # ends by itself: no exception, no hang
        await asyncio.sleep(0.3)
        state = r.sim.state
    lost, gone = guard.events
    assert isinstance(lost, DeviceLost) and isinstance(gone, DeviceGone)
    assert "unplugged" in lost.reason and "no such audio device" in gone.reason
    assert guard.failure is not None and "microphone" in guard.failure and "plugged in" in guard.failure
    assert reaction.stopped == [True]
    assert not state.moving and state.nearest_place != "front door"  # stopped short, standing still
    finished = r.log.of(VoiceTurnFinished)
    assert len(finished) == 1 and finished[0].cancelled  # the drive's turn was cancelled
    spoken = r.spoken()
    assert LOST_MESSAGE in spoken and GONE_MESSAGE in spoken


@pytest.mark.parametrize("fault", ["fail", "hang"])
async def test_the_device_disappears_and_returns(fault: str) -> None:
    holder: list[GuardedSource] = []

    def make(sim: SimRobot) -> AudioSource:
        first = ScriptedMic(command(), fault, until=lambda: sim.state.moving)
        second = ScriptedMic(command(), "end")
        guard = GuardedSource(plan(first, AudioError("no such device"), AudioError("no such device"), second),
                              stall_s=0.5, retry_s=0.1, give_up_s=10.0)
        holder.append(guard)
        return guard

    async with rig(make, sim_speed=1.0) as r:
        guard = holder[0]
        reaction = DeviceReaction(r.pipeline)

        async def on_event(event: DeviceLost | DeviceBack | DeviceGone) -> None:
            await reaction(event)
            if isinstance(event, DeviceLost):
                r.stt.text = "how much battery do you have left"  # what the person says once it is back

        guard.on_event = on_event
        r.stt.text = "go to the front door"
        await r.run()
        state = r.sim.state
    kinds = [type(e) for e in guard.events]
    assert kinds == [DeviceLost, DeviceBack], guard.events
    lost, back = guard.events
    assert isinstance(lost, DeviceLost) and isinstance(back, DeviceBack)
    assert ("unplugged" if fault == "fail" else "no audio from the device for 0.5 s") in lost.reason
    assert back.gone_s > 0.15 and back.at > lost.at
    assert guard.failure is None
    assert reaction.stopped == [True] and not state.moving and state.nearest_place != "front door"
    finished = r.log.of(VoiceTurnFinished)
    assert [f.cancelled for f in finished] == [True, False]
    answer = finished[1].result
    assert answer is not None and "battery" in answer.reply.lower() and any(ch.isdigit() for ch in answer.reply)
    spoken = r.spoken()
    assert spoken.index(LOST_MESSAGE) < spoken.index(BACK_MESSAGE)


async def test_without_the_guard_the_error_is_the_sources_and_the_drive_is_cancelled() -> None:
    """The plain pipeline: the source's error ends `run` (inside an ExceptionGroup, from its
    TaskGroup); the turn is cancelled with it, and so is the drive on the robot. Nothing is
    said: that is what `GuardedSource` + `DeviceReaction` add."""
    def make(sim: SimRobot) -> AudioSource:
        return ScriptedMic(command(), "fail", until=lambda: sim.state.moving)

    async with rig(make, sim_speed=1.0) as r:
        r.stt.text = "go to the front door"
        with pytest.raises(ExceptionGroup) as caught:
            await r.run()
        await asyncio.sleep(0.5)
        state = r.sim.state
    assert caught.group_contains(AudioError, match="unplugged")
    assert not state.moving and state.nearest_place != "front door"
    assert "navigate_to" in [c.name for c in r.log.of(ToolCalled)]  # the drive had started
    assert LOST_MESSAGE not in r.spoken()
