"""The voice pipeline: microphone -> front end -> turn-taking -> assistant -> speech.

    pipeline = VoicePipeline(models, backend, tools, source=room.mic, sink=room.speaker,
                             reference=room.reference, observer=print_event)
    await pipeline.run()          # until the source ends

Tasks, all owned by one `asyncio.TaskGroup` in `run()`:

- capture (the body of `run`): each microphone chunk goes through the `FrontEnd` on its own
  executor (echo cancellation, wake word, VAD); the resulting facts are handled at once;
- speech: `SpeechOutput`'s two stages (synthesis of sentence N+1 overlaps playback of N);
- one *active* task at a time holding the floor: a command (STT, then the assistant's turn,
  then its speech), created when an addressed utterance ends;
- stop checks: short utterances heard while the robot moves, transcribed and matched
  against the stop phrases without any model call.

Control: a wake word while the robot is busy (speaking or answering) is a barge-in: queued
speech is dropped, the speaker stopped and the active task cancelled (an action it started
is cancelled with it). A spoken stop calls the robot's stop tool directly and cancels the
active task -- concurrently, never behind the model.
"""

from __future__ import annotations

import asyncio
import contextvars
import inspect
import logging
import re
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

from robovoice.assistant.events import SentenceReady, ToolCalled, ToolProgressed, ToolReturned, TurnEvent
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.assistant.metrics import TurnMetrics
from robovoice.assistant.robot_tools import RobotTools
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat
from robovoice.audio.streams import AudioSink, AudioSource, converted
from robovoice.audio.vad import Endpointer, SpeechSegmenter
from robovoice.audio.wake import WakeDecider, WakeWordSpotter
from robovoice.audio.wav import write_wav
from robovoice.llm.base import AudioPart, ContentPart, LLMBackend
from robovoice.voice.config import VoiceConfig
from robovoice.voice.echo import PlaybackReference
from robovoice.voice.events import (
    BargedIn,
    PipelineEvent,
    RobotStopped,
    SentenceSpoken,
    StopHeard,
    TranscriptReady,
    UtteranceIgnored,
    VoiceObserver,
    VoiceTurnFinished,
    VoiceTurnStarted,
    WakeWordHeard,
    WakeWordRejected,
)
from robovoice.voice.frontend import FrontEnd, FrontEndResult, HeardPause, HeardUtterance, HeardWake
from robovoice.voice.inference import ModelExecutor
from robovoice.voice.models import VoiceModels
from robovoice.voice.motion import PoseMotionProbe
from robovoice.voice.progress import ProgressNarrator
from robovoice.voice.speech import SpeechOutput
from robovoice.voice.stop import is_stop_command
from robovoice.voice.turns import Action, TurnTaking, Verdict
from robovoice.voice.utterance import OwnWords, Transcribing, Transcription, strip_wake_words, trim_to_wake, wav_bytes
from robovoice.voice.vocabulary import STOP_HINT, command_hint

log = logging.getLogger(__name__)

_WAKE_ONLY_S = 0.2  # without STT: less speech than this after the wake word = wake word alone


@dataclass(slots=True)
class _Turn:
    id: int
    metrics: TurnMetrics
    motion_calls: set[str] = field(default_factory=set)


_current_turn: contextvars.ContextVar[_Turn | None] = contextvars.ContextVar("robovoice_voice_turn", default=None)


@dataclass(slots=True)
class PipelineStats:
    turns: int = 0
    stops: int = 0
    barge_ins: int = 0
    ignored: int = 0
    rejected_wakes: int = 0
    frontend_s: float = 0.0  # wall time in the front end
    frontend_cpu_s: float = 0.0  # CPU time of the front end's thread
    audio_s: float = 0.0


class VoicePipeline:
    """See the module docstring.

    `moving`: tells whether the robot moves (e.g. the sim's state; default: ask the robot's
    pose tool, `motion.PoseMotionProbe`); motion tools called in a running turn count as
    moving anyway. `remote_speaking`: a call's remote participant is
    speaking through a path the pipeline does not play itself (treated like playback).
    `output_dir`: each turn's spoken answer is written there as ``turn-NN.wav``.
    """

    def __init__(
        self,
        models: VoiceModels,
        backend: LLMBackend,
        tools: RobotTools,
        *,
        source: AudioSource,
        sink: AudioSink,
        reference: PlaybackReference | None = None,
        config: VoiceConfig | None = None,
        observer: VoiceObserver | None = None,
        moving: Callable[[], bool] | PoseMotionProbe | None = None,
        remote_speaking: Callable[[], bool] | None = None,
        output_dir: Path | None = None,
        sink_format: AudioFormat | None = None,
        assistant: Callable[..., Assistant] = Assistant,
    ) -> None:
        self.config = config or VoiceConfig()
        self.models = models
        self.source = source
        self.reference = reference
        self.output_dir = output_dir
        self._observer = observer
        self._moving_probe: Callable[[], bool] | PoseMotionProbe = moving or PoseMotionProbe(tools)
        self._remote_probe = remote_speaking
        self.assistant = assistant(backend, tools, observer=self._on_assistant_event)
        self.audio_native = bool(backend.accepts_audio)
        cfg = self.config
        self.front = FrontEnd(
            WakeWordSpotter(models.wake, WakeDecider(cfg.wake)),
            SpeechSegmenter(models.vad, Endpointer(cfg.endpointer)),
            reference,
            cfg.echo,
            playback_detector=models.playback_wake,
            playback_tail_s=cfg.turns.playback_tail_s,
        )
        self.turns = TurnTaking(cfg.turns)
        self.narrator = ProgressNarrator(cfg.speech)
        self._front_exec = ModelExecutor("frontend")
        self._stt_exec = ModelExecutor("stt")
        self._tts_exec = ModelExecutor("tts")
        self.speech = SpeechOutput(models.tts, sink, self._tts_exec, sink_format=sink_format,
                                   on_spoken=self._on_spoken, queue_size=cfg.speech.queue_sentences)
        self.stats = PipelineStats()
        self.results: list[TurnResult] = []
        self._group: asyncio.TaskGroup | None = None
        self._active: asyncio.Task[None] | None = None
        self._active_turn: int | None = None
        self._checks: set[asyncio.Task[None]] = set()
        self._turns: dict[int, _Turn] = {}
        self._next_id = 0
        self._now = 0.0
        self._changed = asyncio.Event()
        self._own_words = OwnWords()
        self.stt = Transcribing(models.stt, self._stt_exec) if models.stt is not None else None
        self.hint = command_hint(cfg.wake_phrase, [], cfg.vocabulary)  # see `refresh_hint`
        if self.audio_native is False and models.stt is None:
            raise ValueError("a text-only backend needs a speech-to-text model")

    # --- running -------------------------------------------------------------------------

    async def run(self, *, finish_timeout_s: float = 120.0) -> None:
        """Listen until the source ends, then let the running turn finish (bounded)."""
        self.front.reset()
        await self.refresh_hint()
        try:
            async with asyncio.TaskGroup() as group:
                self._group = group
                speech = group.create_task(self.speech.run(), name="voice-speech")
                await self._capture()
                if not await self.wait_idle(finish_timeout_s):
                    log.warning("the last turn did not finish within %.0f s of the end of input", finish_timeout_s)
                self._cancel_active()
                for task in list(self._checks):
                    task.cancel()
                speech.cancel()
        finally:
            self._group = None
            for executor in (self._front_exec, self._stt_exec, self._tts_exec):
                await executor.aclose()

    async def refresh_hint(self) -> None:
        """Rebuild the speech-to-text hint from the robot's current tools (`vocabulary`)."""
        try:
            specs = await self.assistant.tools.specs()
        except Exception as exc:  # a robot that cannot list its tools now still gets its commands heard
            log.warning("speech-to-text hint not refreshed (listing the tools failed: %s)", exc)
            return
        self.hint = command_hint(self.config.wake_phrase, specs, self.config.vocabulary)

    def _idle(self) -> bool:
        return (
            (self._active is None or self._active.done())
            and not self._checks
            and not self.speech.busy
            and not self.front.segmenter.endpointer.in_speech
        )

    async def wait_idle(self, timeout: float = 60.0) -> bool:
        """Wait until nothing is being said, answered or spoken; False on timeout."""
        try:
            async with asyncio.timeout(timeout):
                while not self._idle():
                    self._changed.clear()
                    await self._changed.wait()
        except TimeoutError:
            return False
        return True

    async def _capture(self) -> None:
        async for chunk in converted(aiter(self.source), MODEL_FORMAT):
            received = time.perf_counter()
            if self._remote_probe is not None:
                self.front.external_playback = self._remote_probe()
            result = await self._front_exec.run(self.front.process, chunk)
            self.stats.audio_s += chunk.duration_s
            await self._handle(result, received)
        await self._handle(await self._front_exec.run(self.front.flush), time.perf_counter())

    async def _handle(self, result: FrontEndResult, received: float) -> None:
        self._now = result.now
        self.stats.frontend_s += result.compute_s
        self.stats.frontend_cpu_s += result.cpu_s
        self.turns.playback(result.playing or self.speech.busy, result.now)
        if self.turns.expire(result.now):
            log.info("wake word not followed by a command; listening again")
        for event in result.events:
            match event:
                case HeardWake():
                    await self._on_wake(event)
                case HeardPause():
                    self._on_pause(event)
                case HeardUtterance():
                    await self._on_utterance(event, received, result.compute_s)
                case _:
                    pass
        self._changed.set()

    async def _emit(self, event: PipelineEvent) -> None:
        if self._observer is not None:
            result = self._observer(event)
            if inspect.isawaitable(result):
                await result

    # --- what was heard ------------------------------------------------------------------

    def _busy(self) -> bool:
        return (self._active is not None and not self._active.done()) or self.speech.busy

    async def _on_wake(self, event: HeardWake) -> None:
        if not event.near_end:
            self.stats.rejected_wakes += 1
            log.info("wake word at %.2f s rejected: the robot's own playback", event.at)
            await self._emit(WakeWordRejected(event.score, event.at))
            return
        if self._busy():
            self.stats.barge_ins += 1
            cancelled = self._cancel_active()
            self.speech.interrupt()
            await self._emit(BargedIn(event.at, cancelled))
        self.turns.wake(event.at)
        await self._emit(WakeWordHeard(event.score, event.at, event.during_playback))

    def _own_motion(self) -> bool:
        return any(t.motion_calls for t in self._turns.values())

    async def _moving(self) -> bool:
        if self._own_motion():
            return True
        probe = self._moving_probe
        return await probe() if isinstance(probe, PoseMotionProbe) else bool(probe())

    def _moving_hint(self) -> bool:
        """Without waiting: own drives, or the probe's recent answer."""
        if self._own_motion():
            return True
        probe = self._moving_probe
        return probe.cached if isinstance(probe, PoseMotionProbe) else bool(probe())

    # --- speculative speech-to-text ---------------------------------------------------------

    def _on_pause(self, pause: HeardPause) -> None:
        """Start transcribing at the first pause of an utterance that will need it, so the
        transcript is (nearly) ready when the end-of-turn silence confirms the end."""
        if self.stt is None or self._group is None:
            return
        short = pause.at - pause.onset <= self.config.turns.stop_max_s
        addressed = self.turns.addressed(pause.onset, pause.at)
        if self.audio_native and not (addressed and short):
            return  # audio goes to the model as it is; only short commands are checked for a stop
        if not addressed and not (self._moving_hint() and short):
            return
        group = self._group
        self.stt.speculate(pause.onset, pause.at, trim_to_wake(pause.audio, self.turns.pending_wake),
                           lambda coro: group.create_task(coro, name="voice-stt-speculative"),
                           self.hint if addressed else STOP_HINT)

    async def _on_utterance(self, utt: HeardUtterance, received: float, compute_s: float) -> None:
        short = utt.duration_s <= self.config.turns.stop_max_s
        moving = short and not self.turns.addressed(utt.start, utt.end) and await self._moving()
        verdict = self.turns.classify(utt.start, utt.end, moving=moving)
        own_voice = utt.playback_share > 0.5 and not utt.near_end
        hint = STOP_HINT if verdict.action is Action.STOP_CHECK else self.hint
        speculation = self.stt.take(utt.start, utt.end, hint) if self.stt is not None else None
        if verdict.action is Action.COMMAND and (verdict.wake_at is not None or not own_voice):
            self._start_command(utt, verdict, received, compute_s, speculation)
        elif verdict.action is Action.STOP_CHECK:
            # no acoustic gate here: a missed stop is worse than a needless one, and the robot's
            # own "stop" is recognised by its words (`OwnWords`) instead
            assert self._group is not None
            task = self._group.create_task(self._stop_check(utt, received, speculation), name="voice-stop-check")
            self._checks.add(task)
            task.add_done_callback(self._check_done)
        else:
            if speculation is not None:
                speculation.cancel()
            await self._ignore("own_voice" if own_voice else verdict.reason or "no_wake_word", utt)

    def _check_done(self, task: asyncio.Task[None]) -> None:
        self._checks.discard(task)
        self._changed.set()

    async def _ignore(self, reason: str, utt: HeardUtterance, text: str | None = None) -> None:
        self.stats.ignored += 1
        log.info("utterance %.2f-%.2f s ignored: %s", utt.start, utt.end, reason)
        await self._emit(UtteranceIgnored(reason, utt.start, utt.end, text))

    def _cancel_active(self) -> int | None:
        """Cancel the task holding the floor (unless it is the caller); its turn id."""
        task = self._active
        if task is None or task.done() or task is asyncio.current_task():
            return None
        task.cancel()
        return self._active_turn

    def _new_turn(self, metrics: TurnMetrics) -> _Turn:
        self._next_id += 1
        turn = _Turn(self._next_id, metrics)
        self._turns[turn.id] = turn
        return turn

    def _start_command(
        self,
        utt: HeardUtterance,
        verdict: Verdict,
        received: float,
        compute_s: float,
        speculation: Transcription | None,
    ) -> None:
        assert self._group is not None
        self._cancel_active()
        metrics = TurnMetrics(start=received)
        metrics.mark("endpoint", received + compute_s)
        turn = self._new_turn(metrics)
        self._active_turn = turn.id
        self._active = self._group.create_task(self._command(turn, utt, verdict, speculation),
                                               name=f"voice-turn-{turn.id}")
        self._active.add_done_callback(lambda _: self._changed.set())

    async def _transcribe(
        self, audio: AudioChunk, metrics: TurnMetrics, speculation: Transcription | None, hint: str
    ) -> str:
        """The transcript: from the speculative run when it covers the utterance, else now."""
        assert self.stt is not None
        text, took_ms = await speculation if speculation is not None else await self.stt.transcribe(audio, hint)
        metrics.stt_ms += took_ms
        metrics.mark("transcript", max(metrics.start, time.perf_counter()))
        return text

    async def _command(
        self,
        turn: _Turn,
        utt: HeardUtterance,
        verdict: Verdict,
        speculation: Transcription | None,
    ) -> None:
        token = _current_turn.set(turn)
        metrics = turn.metrics
        result: TurnResult | None = None
        started = cancelled = False
        try:
            audio = trim_to_wake(utt.audio, verdict.wake_at)
            content: str | tuple[ContentPart, ...]
            text = ""
            if self.audio_native and (self.stt is None or utt.duration_s > self.config.turns.stop_max_s):
                if verdict.wake_at is not None and utt.end - verdict.wake_at < _WAKE_ONLY_S:
                    self.turns.rearm(utt.end)
                    await self._ignore("wake_only", utt)
                    return
                content = (AudioPart(wav_bytes(audio)),)
            else:
                raw = await self._transcribe(audio, metrics, speculation, self.hint)
                text = strip_wake_words(raw, self.config.wake_phrase) if verdict.wake_at is not None else raw.strip()
                await self._emit(TranscriptReady(text, metrics.stt_ms))
                if not re.search(r"[A-Za-z0-9]", text):
                    self.turns.rearm(utt.end)
                    await self._ignore("wake_only" if verdict.wake_at is not None else "empty", utt, raw)
                    return
                if is_stop_command(text):
                    await self._stop(text, utt.end, turn)
                    return
                content = (AudioPart(wav_bytes(audio)),) if self.audio_native else text
            mode: Literal["text", "audio"] = "audio" if isinstance(content, tuple) else "text"
            self.stats.turns += 1
            started = True
            self.turns.turn_started()
            await self._emit(VoiceTurnStarted(turn.id, mode, text, audio.duration_s, verdict.follow_up))
            result = await self.assistant.turn(content, metrics=metrics)
            self.results.append(result)
            self.turns.turn_finished(asked_question=result.reply.rstrip().endswith("?"))
            turn.motion_calls.clear()
            await self.refresh_hint()  # the tools may have changed during the turn
            await self.speech.idle(timeout=120.0)
        except asyncio.CancelledError:
            cancelled = True
            if started:
                self.turns.turn_cancelled()
            raise
        finally:
            _current_turn.reset(token)
            self._turns.pop(turn.id, None)
            if started:
                await self._emit(VoiceTurnFinished(turn.id, result, cancelled, metrics.as_dict()))
            self._save_answer(turn.id)

    # --- stop ----------------------------------------------------------------------------------

    async def _stop_check(
        self, utt: HeardUtterance, received: float, speculation: Transcription | None
    ) -> None:
        metrics = TurnMetrics(start=received)
        if self.stt is None:
            await self._ignore("no_stt_for_stop_check", utt)
            return
        text = await self._transcribe(utt.audio, metrics, speculation, STOP_HINT)
        if not is_stop_command(strip_wake_words(text, self.config.wake_phrase)):
            await self._ignore("not_a_stop", utt, text)
            return
        if utt.playback_share > 0.3 and self._own_words.contains(text):
            await self._ignore("own_voice", utt, text)  # the robot heard itself say "stop"
            return
        turn = self._new_turn(metrics)
        try:
            await self._stop(text, utt.end, turn)
        finally:
            self._turns.pop(turn.id, None)
            self._save_answer(turn.id)

    async def _stop(self, text: str, at: float, turn: _Turn) -> None:
        """Stop the robot now: its stop tool, straight; the active task cancelled; no model."""
        self.stats.stops += 1
        metrics, tool = turn.metrics, self.config.stop_tool
        cancelled = self._cancel_active()
        self.speech.interrupt()
        metrics.mark(f"tool_call:{tool}")
        called = ToolCalled(f"local-stop-{turn.id}", tool, {})
        await self._emit(StopHeard(text, at, cancelled))
        started = time.perf_counter()
        try:
            async with asyncio.timeout(self.config.stop_timeout_s):
                outcome = await self.assistant.tools.call(tool, {})
            ok, detail = not outcome.is_error, outcome.text
        except TimeoutError:
            ok, detail = False, f"the stop tool did not answer within {self.config.stop_timeout_s:g} s"
        took_ms = (time.perf_counter() - started) * 1000.0
        metrics.tools_ms += took_ms
        metrics.mark(f"tool_result:{tool}")
        log.info("spoken stop: %s (%s)", "robot stopped" if ok else "STOP FAILED", detail)
        await self._emit(RobotStopped(ok, detail, metrics.marks[f"tool_result:{tool}"]))
        reply = self.config.speech.stop_reply if ok else "I could not stop the robot!"
        self.speech.say(reply, turn=turn.id, kind="stop", metrics=metrics)
        returned = ToolReturned(called.call_id, tool, detail, not ok, took_ms)
        self.results.append(TurnResult(reply, (called,), (returned,), metrics))
        await self.speech.idle(timeout=30.0)

    # --- the assistant's events -------------------------------------------------------------------

    async def _on_assistant_event(self, event: TurnEvent) -> None:
        turn = _current_turn.get()
        turn_id = turn.id if turn is not None else None
        metrics = turn.metrics if turn is not None else None
        now = time.monotonic()
        match event:
            case SentenceReady(text):
                self.speech.say(text, turn=turn_id, kind="reply", metrics=metrics)
            case ToolCalled(call_id, name, arguments):
                if turn is not None and name in self.config.motion_tools:
                    turn.motion_calls.add(call_id)
                ack = self.narrator.on_call(name, arguments, now)
                if ack:
                    self.speech.say(ack, turn=turn_id, kind="progress", metrics=metrics)
            case ToolProgressed(name, progress, total, message):
                line = self.narrator.on_progress(name, progress, total, message, now)
                if line:
                    self.speech.say(line, turn=turn_id, kind="progress", metrics=metrics)
            case ToolReturned(call_id):
                if turn is not None:
                    turn.motion_calls.discard(call_id)
            case _:
                pass
        await self._emit(event)

    async def _on_spoken(self, event: SentenceSpoken) -> None:
        self._own_words.add(event.text)
        await self._emit(event)

    def _save_answer(self, turn_id: int) -> None:
        audio = self.speech.take_recording(turn_id)
        if audio is None or self.output_dir is None:
            return
        self.output_dir.mkdir(parents=True, exist_ok=True)
        write_wav(self.output_dir / f"turn-{turn_id:02d}.wav", audio)
