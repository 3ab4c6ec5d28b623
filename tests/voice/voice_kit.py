"""Test kit for the voice pipeline: a session (sim robot over MCP + simulated room + pipeline),
an event log with bounded waits, model fakes keyed to the test audio, audio builders."""

from __future__ import annotations

import asyncio
import json
import math
import re
from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

import numpy as np

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.robot_tools import RobotTools, Toolbox
from robovoice.audio.fakes import EnergyVAD, ToneSynthesizer, ToneWakeDetector
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, float32_to_int16
from robovoice.audio.stt import Transcript
from robovoice.audio.wav import read_wav
from robovoice.config import RobotConfig, VoiceConfig
from robovoice.llm.base import LLMBackend
from robovoice.manifest.voice import VoiceDecl
from robovoice.sim import SimRobot
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import PipelineEvent
from robovoice.voice.models import VoiceModels
from robovoice.voice.pipeline import VoicePipeline
from robovoice.voice.roles import VoiceRoles
from robovoice.voice.room import EchoPath, SimulatedRoom

DATA = Path(__file__).resolve().parent.parent / "data"
EVAL_AUDIO = DATA / "eval" / "audio"
TEST_AUDIO = DATA / "audio"
RATE = MODEL_FORMAT.rate
WAKE_TONE_HZ = 1000.0
ROOM_ECHO = EchoPath()  # the robot's speaker 6 dB louder at its microphone than the direct path, 4 reflections

E = TypeVar("E")


def clip(name: str) -> AudioChunk:
    """A committed clip: ``eval/<id>`` or ``audio/<id>`` under tests/data."""
    folder, _, clip_id = name.partition("/")
    return read_wav((EVAL_AUDIO if folder == "eval" else TEST_AUDIO) / f"{clip_id}.wav")


def clip_text(clip_id: str) -> str:
    specs = json.loads((EVAL_AUDIO / "clips.json").read_text(encoding="utf-8"))
    return str(next(s["text"] for s in specs if s["id"] == clip_id))


def sim_voice_roles() -> VoiceRoles:
    """The voice roles and phrases the sim robot's manifests declare."""
    import robovoice.sim
    from robovoice.manifest.loader import load_manifest_dir

    loaded = load_manifest_dir(Path(robovoice.sim.__file__).parent / "manifests")
    sections: dict[str, VoiceDecl] = {}
    for item in loaded.manifests.values():
        for tool in item.manifest.tools:
            if tool.voice is not None:
                sections[tool.name] = tool.voice
        for snapshot in item.manifest.snapshots:
            if snapshot.voice is not None:
                sections[snapshot.name] = snapshot.voice
    return VoiceRoles.from_tools(sections)


# --- model fakes keyed to synthetic audio ------------------------------------------------------


class SettableTranscriber:
    """Speech-to-text fake: returns `text` (set by the test before each utterance), or what
    `by_length` gives for the audio's duration; remembers each run's hint and duration."""

    def __init__(self, text: str = "") -> None:
        self.text = text
        self.by_length: Callable[[float], str] | None = None
        self.calls = 0
        self.hints: list[str] = []
        self.durations: list[float] = []

    def transcribe(self, audio: AudioChunk, hint: str = "") -> Transcript:
        self.calls += 1
        self.hints.append(hint)
        self.durations.append(audio.duration_s)
        text = self.by_length(audio.duration_s) if self.by_length is not None else self.text
        return Transcript(text, audio.duration_s)


def fake_models(transcriber: SettableTranscriber | None = None) -> VoiceModels:
    return VoiceModels(wake=ToneWakeDetector(), vad=EnergyVAD(), stt=transcriber or SettableTranscriber(),
                       tts=ToneSynthesizer(seconds_per_char=0.02), playback_wake=ToneWakeDetector())


def tone(seconds: float, hz: float = WAKE_TONE_HZ, level_db: float = -20.0) -> AudioChunk:
    t = np.arange(round(seconds * RATE)) / RATE
    x = math.sqrt(2) * 10 ** (level_db / 20) * np.sin(2 * np.pi * hz * t)
    return AudioChunk(float32_to_int16(x.astype(np.float32)), MODEL_FORMAT)


def babble(seconds: float, level_db: float = -20.0, seed: int = 0) -> AudioChunk:
    """Speech-like noise (band-limited, amplitude-modulated) for the energy VAD."""
    rng = np.random.default_rng(seed)
    n = round(seconds * RATE)
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, 1 / RATE)
    spec[(f < 200) | (f > 3500)] = 0
    x = np.fft.irfft(spec, n)
    x *= 0.6 + 0.4 * np.sin(2 * np.pi * 4 * np.arange(n) / RATE)
    x *= 10 ** (level_db / 20) / (np.sqrt(np.mean(x * x)) + 1e-12)
    return AudioChunk(float32_to_int16(x.astype(np.float32)), MODEL_FORMAT)


def join(*parts: AudioChunk) -> AudioChunk:
    return AudioChunk(np.concatenate([p.samples for p in parts]), MODEL_FORMAT)


def wake_command(seconds: float = 1.0) -> AudioChunk:
    """'Hey Jarvis' (the tone) followed at once by a command (speech-like noise)."""
    return join(tone(0.5), babble(seconds))


# --- the session ------------------------------------------------------------------------------


class EventLog:
    """Every pipeline event, in order, with bounded waits for the next matching one."""

    def __init__(self) -> None:
        self.events: list[PipelineEvent] = []
        self._changed = asyncio.Event()

    def __call__(self, event: PipelineEvent) -> None:
        self.events.append(event)
        self._changed.set()

    def of(self, kind: type[E]) -> list[E]:
        return [e for e in self.events if isinstance(e, kind)]

    async def wait_for(self, kind: type[E], where: Callable[[E], bool] = lambda _: True,
                       timeout: float = 30.0, after: int = 0) -> E:
        """The first event of `kind` (from index `after`) for which `where` holds."""
        async with asyncio.timeout(timeout):
            while True:
                for e in self.events[after:]:
                    if isinstance(e, kind) and where(e):
                        return e
                self._changed.clear()
                await self._changed.wait()


@dataclass
class Session:
    room: SimulatedRoom
    pipeline: VoicePipeline
    sim: SimRobot
    tools: RobotTools
    log: EventLog

    async def say(self, audio: AudioChunk, *, gap_s: float = 0.3, timeout: float = 30.0) -> None:
        """Say `audio` into the room and wait until it has been spoken."""
        speech = self.room.say(audio, gap_s=gap_s)
        await speech.finished(timeout)

    async def settle(self, timeout: float = 60.0) -> None:
        """Wait until the pipeline is idle (everything heard is answered and spoken)."""
        await self.room.until(self.room.now + 0.7, timeout)  # the end-of-turn silence
        assert await self.pipeline.wait_idle(timeout), "the pipeline did not become idle"


async def wait_until(predicate: Callable[[], bool], room: SimulatedRoom, timeout: float = 30.0) -> None:
    """Wait (on the room's clock ticks, bounded) until `predicate()` holds."""
    async with asyncio.timeout(timeout):
        while not predicate():
            await room.until(room.now + 0.08, timeout)


@asynccontextmanager
async def voice_session(
    models: VoiceModels,
    backend: LLMBackend,
    *,
    sim_speed: float = 20.0,
    speed: float = 1.0,
    echo: EchoPath | None = ROOM_ECHO,
    noise: AudioChunk | None = None,
    config: VoiceConfig | None = None,
    output_dir: Path | None = None,
    setup: str = "",
    manifests: Path | None = None,
    tools: Callable[[RobotTools], Toolbox] | None = None,
    sim_moving: bool = True,
    **pipeline_options: Any,
) -> AsyncIterator[Session]:
    """The embedded sim robot (over a real MCP client; `manifests`: a folder replacing the sim's),
    a room and a running pipeline. `config`: the ``[voice]`` settings; `tools`: wraps the robot's
    tools (a test's stand-in); `sim_moving`: tell the pipeline whether the robot moves from the
    sim's state (else it asks the robot's pose tool, as for a remote robot)."""
    async with connect_robot(RobotConfig(address=f"sim://?speed={sim_speed:g}", manifests=manifests)) as link:
        sim = link.sim
        assert sim is not None
        toolbox = tools(link.tools) if tools is not None else link.tools
        if setup:
            await sim.apply_setup(setup)
        room = SimulatedRoom(speed=speed, echo=echo, noise=noise)
        log = EventLog()
        pipeline = VoicePipeline(models, backend, toolbox, source=room.mic, sink=room.speaker,
                                 reference=room.reference, config=PipelineConfig.from_config(config), observer=log,
                                 moving=(lambda: sim.state.moving) if sim_moving else None, output_dir=output_dir,
                                 **pipeline_options)
        async with asyncio.TaskGroup() as group:
            group.create_task(pipeline.run(finish_timeout_s=15.0), name="pipeline")
            try:
                await room.until(room.now + 0.01)  # listening: the robot's tools and voice roles are known
                yield Session(room, pipeline, sim, link.tools, log)
            finally:
                room.close()


# --- a fake LLM that routes by keywords (the test then needs the transcript to be right) ----------

_ROUTES: list[tuple[tuple[str, ...], str, dict[str, Any]]] = [
    (("projector", "off"), "set_projector_power", {"on": False}),
    (("projector",), "set_projector_power", {"on": True}),
    (("anna",), "start_video_call", {"contact": "Anna"}),
    (("call",), "end_video_call", {}),  # "end the call" (speech-to-text also hears "and the call")
    (("kitchen",), "navigate_to", {"target": "kitchen"}),
    (("front", "door"), "navigate_to", {"target": "front door"}),
    (("bedroom",), "navigate_to", {"target": "bedroom"}),
    (("battery",), "get_battery_state", {}),
]


def keyword_router(request: Any) -> Any:
    """A `CallbackReply` function: a tool call chosen by keywords of the user's words, then a
    short sentence once the tool has answered."""
    from robovoice.llm.fake_server import ScriptedCall, TextReply, ToolCallReply

    messages = request.messages
    if messages and messages[-1].get("role") == "tool":
        name = messages[-2]["tool_calls"][0]["function"]["name"].replace("_", " ")
        figure = re.search(r"\d+(?:\.\d+)?", str(messages[-1].get("content", "")))
        return TextReply(f"Done: {name}" + (f", {figure.group(0)}." if figure and "battery" in name else "."))
    words = re.findall(r"[a-z]+", request.last_user_text.lower())
    for keys, tool, args in _ROUTES:
        if all(k in words for k in keys):
            return ToolCallReply((ScriptedCall(tool, args),))
    return TextReply("Sorry, I did not catch that.")
