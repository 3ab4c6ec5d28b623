"""Audio cases for `robovoice eval` (DESIGN.md §6): each clip through the whole pipeline.

    async with open_clip_runner(config) as audio:
        report = await run_eval(cases, backend, open_robot, audio=audio)

Every clip is spoken into a fresh `SimulatedRoom` (echo of the robot's answer included)
and heard by a fresh `VoicePipeline` — wake word, VAD, speech-to-text (or the audio itself
for an audio-capable backend), the assistant's turn, speech — sharing the loaded models.
The turns the clip led to (none when the assistant rightly did nothing: no wake word) come
back as one frozen `ClipOutcome` and are scored; a spoken stop counts as its stop tool's call.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from dataclasses import dataclass
from pathlib import Path

from robovoice.assistant.robot_tools import RobotTools
from robovoice.audio.wav import read_wav
from robovoice.config import Config
from robovoice.eval.cases import Case
from robovoice.eval.runner import ClipOutcome
from robovoice.llm.base import LLMBackend
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import PipelineEvent, TranscriptReady, UtteranceIgnored, WakeWordHeard
from robovoice.voice.models import VoiceModels, load_voice_models
from robovoice.voice.pipeline import VoicePipeline
from robovoice.voice.room import SimulatedRoom

log = logging.getLogger(__name__)


@dataclass(frozen=True, slots=True)
class VoiceClipRunner:
    """`robovoice.eval.runner.ClipRunner` over the voice pipeline (see module docstring).
    `speed`: how much faster than real time the room plays the clip."""

    models: VoiceModels
    config: PipelineConfig
    speed: float = 1.0
    turn_timeout_s: float = 180.0
    record_dir: Path | None = None  # each case's session (voice.recording) goes here as <id>.wav

    async def run_clip(self, case: Case, backend: LLMBackend, tools: RobotTools) -> ClipOutcome:
        assert case.audio is not None
        audio = read_wav(case.audio)
        room = SimulatedRoom(speed=self.speed, record=self.record_dir is not None)
        speech = room.say(audio, gap_s=0.3)
        heard: list[PipelineEvent] = []
        pipeline = VoicePipeline(self.models, backend, tools, source=room.mic,
                                 sink=room.speaker, reference=room.reference, config=self.config,
                                 observer=heard.append)

        async def speak() -> None:
            try:
                await speech.finished(timeout=audio.duration_s / self.speed + 30.0)
                await room.until(room.now + self.config.endpointer.end_silence_s + 0.3)
                if not await pipeline.wait_idle(self.turn_timeout_s):
                    log.warning("case %s: the pipeline was still busy after %.0f s", case.id, self.turn_timeout_s)
            finally:
                room.close()

        async with asyncio.TaskGroup() as group:
            group.create_task(pipeline.run(finish_timeout_s=10.0), name=f"eval-{case.id}-pipeline")
            group.create_task(speak(), name=f"eval-{case.id}-speak")
        if self.record_dir is not None:
            from robovoice.voice.recording import write_session

            write_session(self.record_dir / f"{case.id}.wav", room, origin=speech.start)
        return ClipOutcome(
            turns=tuple(pipeline.results),
            wake_words=sum(isinstance(e, WakeWordHeard) for e in heard),
            transcripts=tuple(e.text for e in heard if isinstance(e, TranscriptReady)),
            ignored=tuple(f"{e.reason}: {e.text}" if e.text else e.reason
                          for e in heard if isinstance(e, UtteranceIgnored)),
            stops=pipeline.stats.stops,
        )


@asynccontextmanager
async def open_clip_runner(
    config: Config | None = None, *, models: VoiceModels | None = None, speed: float = 1.0,
    record_dir: Path | None = None,
) -> AsyncIterator[VoiceClipRunner]:
    """Load the voice models (unless given) and yield the clip runner for audio cases."""
    settings = (config or Config()).voice
    if models is None:
        models = await asyncio.to_thread(load_voice_models, wake_model=settings.wake_model, stt=settings.stt,
                                           wake_phases=settings.wake_phases)
    yield VoiceClipRunner(models, PipelineConfig.from_config(settings), speed, record_dir=record_dir)
