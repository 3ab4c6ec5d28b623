"""The voice pipeline: microphone -> listener -> router -> command turn -> assistant -> speech.

    pipeline = VoicePipeline(models, backend, tools, source=room.mic, sink=room.speaker,
                             reference=room.reference, observer=print_event)
    await pipeline.run()          # until the source ends

This module only assembles the parts, each with one job, and runs them. Tasks, all owned by
one `asyncio.TaskGroup` in `run()`:

- capture (the body of `run`): each microphone chunk goes through the `Listener` on its own
  executor (echo cancellation, wake word, VAD); the `Router` handles what was heard at once,
  never waiting on the network or a model;
- speech: `SpeechOutput`'s two stages (synthesis of sentence N+1 overlaps playback of N);
- one command turn at a time holding the floor (`Floor`, `command.CommandTurn`: STT, the
  assistant's turn with the turn's own observer, its speech); stop checks beside it
  (`stopping.StopController`); speculative transcriptions;
- the motion watch (`motion.MotionWatch`: the robot's pose tool asked in the background) and
  the tool watch (the robot's voice roles and speech-to-text hint, rebuilt when its tools change).

Latency origins: a command turn places the user's last word (the utterance's end, in stream
time) on the wall clock where its stages are timed (`TurnMetrics.speech_end`). A source that
knows when it captured each sample says so with a ``capture_time(stream_s)`` method
(`SimulatedRoom`'s microphone, like a sound card's buffer timestamps); otherwise each chunk's
arrival is noted in a `clock.StreamAnchor`, with the source's ``speed`` attribute when it plays
faster than real time (else real time).

Control: a wake word while the robot is busy (speaking or answering) is a barge-in: queued
speech is dropped, the speaker stopped and the active turn cancelled (an action it started is
cancelled with it). A spoken stop calls the robot's stop tool (its manifest's ``stop`` role)
directly and cancels the active turn -- concurrently, never behind the model.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Callable
from pathlib import Path

from robovoice.assistant.events import notify
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.assistant.robot_tools import Toolbox
from robovoice.audio.format import MODEL_FORMAT, AudioFormat
from robovoice.audio.streams import AudioSink, AudioSource, converted
from robovoice.audio.vad import Endpointer, SpeechSegmenter
from robovoice.audio.wake import WakeDecider, WakeWordSpotter
from robovoice.llm.base import LLMBackend, ToolSpec
from robovoice.voice.answers import AnswerRecorder
from robovoice.voice.clock import StreamAnchor
from robovoice.voice.command import Commands
from robovoice.voice.config import PipelineConfig
from robovoice.voice.echo import PlaybackReference
from robovoice.voice.events import PipelineEvent, SentenceSpoken, VoiceObserver
from robovoice.voice.floor import Floor, PipelineStats
from robovoice.voice.inference import ModelExecutor
from robovoice.voice.listener import Listener
from robovoice.voice.models import VoiceModels
from robovoice.voice.motion import MotionWatch
from robovoice.voice.progress import ProgressNarrator
from robovoice.voice.roles import NO_STOP_WARNING, VoiceRoles
from robovoice.voice.router import Router
from robovoice.voice.speech import SpeechOutput
from robovoice.voice.stopping import StopController
from robovoice.voice.turns import TurnTaking
from robovoice.voice.utterance import OwnWords, Transcribing
from robovoice.voice.vocabulary import command_hint

log = logging.getLogger(__name__)

__all__ = ["PipelineStats", "VoicePipeline"]

TOOL_WATCH_S = 2.0  # how often the tool watch looks for a changed tool list (no network unless it changed)


class VoicePipeline:
    """See the module docstring.

    `tools`: the robot's tools (`RobotTools`); their manifests' voice sections say which tool
    stops the robot, which move it and which tells its pose. `moving`: a local answer to "is
    the robot moving?" (e.g. the embedded sim's state; default: ask the pose tool in the
    background). `remote_speaking`: a call's remote participant is speaking through a path the
    pipeline does not play itself (treated like playback). `output_dir`: each turn's spoken
    answer is written there as ``turn-NN.wav``. `config`: default `PipelineConfig.from_config()`.
    """

    def __init__(
        self,
        models: VoiceModels,
        backend: LLMBackend,
        tools: Toolbox,
        *,
        source: AudioSource,
        sink: AudioSink,
        reference: PlaybackReference | None = None,
        config: PipelineConfig | None = None,
        observer: VoiceObserver | None = None,
        moving: Callable[[], bool] | None = None,
        remote_speaking: Callable[[], bool] | None = None,
        output_dir: Path | None = None,
        sink_format: AudioFormat | None = None,
        assistant: Callable[..., Assistant] = Assistant,
    ) -> None:
        cfg = self.config = config or PipelineConfig.from_config()
        self.models = models
        self.source = source
        self.tools = tools
        self._observer = observer
        self._remote_probe = remote_speaking
        self.audio_native = bool(backend.accepts_audio)
        if self.audio_native is False and models.stt is None:
            raise ValueError("a text-only backend needs a speech-to-text model")
        self.assistant = assistant(backend, tools)
        self.listener = Listener(
            WakeWordSpotter(models.wake, WakeDecider(cfg.wake)),
            SpeechSegmenter(models.vad, Endpointer(cfg.endpointer)),
            reference,
            cfg.echo,
            playback_detector=models.playback_wake,
            playback_tail_s=cfg.turns.playback_tail_s,
        )
        self._front_exec = ModelExecutor("frontend")
        self._stt_exec = ModelExecutor("stt")
        self._tts_exec = ModelExecutor("tts")
        self._own_words = OwnWords()
        self.speech = SpeechOutput(models.tts, sink, self._tts_exec, sink_format=sink_format,
                                   on_spoken=self._on_spoken, queue_size=cfg.speech.queue_sentences)
        self.stt = Transcribing(models.stt, self._stt_exec) if models.stt is not None else None
        self.stats = PipelineStats()
        self.floor = Floor()
        self.turns = TurnTaking(cfg.turns)
        self.motion = MotionWatch(tools, moving)
        self.narrator = ProgressNarrator(cfg.speech)
        self.answers = AnswerRecorder(self.speech, output_dir)
        self.stopper = StopController(cfg, tools, speech=self.speech, floor=self.floor, answers=self.answers,
                                      stats=self.stats, emit=self._emit, stt=self.stt, own_words=self._own_words)
        self.commands = Commands(cfg, self.assistant, audio_native=self.audio_native, stt=self.stt,
                                 turns=self.turns, speech=self.speech, narrator=self.narrator, motion=self.motion,
                                 stopper=self.stopper, answers=self.answers, floor=self.floor, stats=self.stats,
                                 emit=self._emit, after_turn=self.refresh_tools)
        self.router = Router(cfg, audio_native=self.audio_native, stt=self.stt, turns=self.turns,
                             speech=self.speech, motion=self.motion, commands=self.commands, stopper=self.stopper,
                             floor=self.floor, stats=self.stats, emit=self._emit)
        # a source's own pace and capture clock: optional, not part of the AudioSource protocol
        self.anchor = StreamAnchor(float(getattr(source, "speed", 1.0)))
        captured = getattr(source, "capture_time", None)
        self.commands.wall_time = captured if callable(captured) else self.anchor.wall_time
        self.stopper.wall_time = self.commands.wall_time
        self.roles = VoiceRoles()
        self.commands.hint = command_hint(cfg.wake_phrase, [], cfg.vocabulary)
        self._listed: list[ToolSpec] | None = None

    @property
    def results(self) -> list[TurnResult]:
        """Every turn's result so far (a spoken stop counts as its stop tool's call)."""
        return self.answers.results

    @property
    def hint(self) -> str:
        """The speech-to-text hint for commands (`vocabulary.command_hint`)."""
        return self.commands.hint

    # --- running -------------------------------------------------------------------------

    async def run(self, *, finish_timeout_s: float = 120.0) -> None:
        """Listen until the source ends, then let the running turn finish (bounded)."""
        self.listener.reset()
        await self.refresh_tools()
        try:
            async with asyncio.TaskGroup() as group:
                self.floor.attach(group)
                background = [group.create_task(self.speech.run(), name="voice-speech"),
                              group.create_task(self.motion.run(), name="voice-motion-watch"),
                              group.create_task(self._watch_tools(), name="voice-tool-watch")]
                await self._capture()
                if not await self.wait_idle(finish_timeout_s):
                    log.warning("the last turn did not finish within %.0f s of the end of input", finish_timeout_s)
                self.floor.cancel_all()
                for task in background:
                    task.cancel()
        finally:
            self.floor.attach(None)
            for executor in (self._front_exec, self._stt_exec, self._tts_exec):
                await executor.aclose()

    async def refresh_tools(self) -> None:
        """Take the robot's voice roles and the speech-to-text hint from its current tools
        (cheap when they have not changed: no request is made then)."""
        try:
            specs = await self.tools.specs()
        except Exception as exc:  # a robot that cannot list its tools now still gets its commands heard
            log.warning("robot tools not refreshed (listing them failed: %s)", exc)
            return
        if specs is self._listed:
            return
        self._listed = specs
        cfg = self.config
        self.commands.hint = command_hint(cfg.wake_phrase, specs, cfg.vocabulary)
        roles = VoiceRoles.from_tools(self.tools.voice())
        if roles != self.roles:
            log.info("robot voice roles: %s", roles.describe())
            if roles.stop is None:
                log.warning(NO_STOP_WARNING)
        self.roles = self.commands.roles = self.stopper.roles = self.narrator.roles = roles
        self.motion.set_pose_tool(roles.pose)

    async def _watch_tools(self) -> None:
        while True:
            await asyncio.sleep(TOOL_WATCH_S)
            await self.refresh_tools()

    def _idle(self) -> bool:
        return self.floor.idle and not self.speech.busy and not self.listener.segmenter.endpointer.in_speech

    async def wait_idle(self, timeout: float = 60.0) -> bool:
        """Wait until nothing is being said, answered or spoken; False on timeout."""
        try:
            async with asyncio.timeout(timeout):
                while not self._idle():
                    self.floor.changed.clear()
                    await self.floor.changed.wait()
        except TimeoutError:
            return False
        return True

    async def _capture(self) -> None:
        async for chunk in converted(aiter(self.source), MODEL_FORMAT):
            received = time.perf_counter()
            self.anchor.observe(received, chunk.end_timestamp)
            if self._remote_probe is not None:
                self.listener.external_playback = self._remote_probe()
            heard = await self._front_exec.run(self.listener.process, chunk)
            self.stats.audio_s += chunk.duration_s
            await self.router.handle(heard, received)
        await self.router.handle(await self._front_exec.run(self.listener.flush), time.perf_counter())

    async def _emit(self, event: PipelineEvent) -> None:
        await notify(self._observer, event)

    async def _on_spoken(self, event: SentenceSpoken) -> None:
        self._own_words.add(event.text)
        await self._emit(event)
