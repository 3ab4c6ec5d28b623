"""Command turns: an addressed utterance -> its transcript (or audio) -> the assistant's turn
-> the robot's speech. One turn holds the floor at a time (`floor.Floor`).

Data goes one way: the utterance comes from the listener, the turn hands it to the
assistant, and the turn's own observer (`CommandTurn.on_event`, passed to
`Assistant.turn`) sends what the assistant produces to speech: its sentences, the tools'
spoken acknowledgements and progress (`progress.ProgressNarrator`), and takes back an
acknowledgement not yet played when its tool fails at once. A turn's events carry its
number and metrics from that observer; nothing is looked up in shared state.
"""

from __future__ import annotations

import asyncio
import re
import time
from collections.abc import Awaitable, Callable
from typing import Literal

from robovoice.assistant.events import SentenceReady, ToolCalled, ToolProgressed, ToolReturned, TurnEvent
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.assistant.metrics import TurnMetrics
from robovoice.audio.format import AudioChunk
from robovoice.audio.stt import Transcript
from robovoice.llm.base import AudioPart, ContentPart
from robovoice.voice.answers import AnswerRecorder
from robovoice.voice.confidence import doubtful, too_noisy, turned_away_with, unsure_reason
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import Emit, TranscriptReady, VoiceTurnFinished, VoiceTurnStarted
from robovoice.voice.floor import Floor, PipelineStats, report_ignored
from robovoice.voice.lastword import last_word_end
from robovoice.voice.listener import HeardUtterance
from robovoice.voice.motion import MotionWatch
from robovoice.voice.progress import ProgressNarrator
from robovoice.voice.roles import VoiceRoles
from robovoice.voice.speech import SpeechOutput
from robovoice.voice.stop import is_stop_command, says_stop
from robovoice.voice.stopping import StopController
from robovoice.voice.turns import TurnTaking, Verdict
from robovoice.voice.utterance import (
    WAKE_PHRASE_S,
    Transcribing,
    Transcription,
    addressed_elsewhere,
    names_robot,
    strip_wake_words,
    trim_to_wake,
    wav_bytes,
)
from robovoice.voice.vocabulary import restore

WAKE_ONLY_S = 0.2  # without STT: less speech than this after the wake word = wake word alone
# "One moment." waits at least this long for the model even when speech-to-text already used up
# the user's patience: a fast model's answer is better than a filler just before it
MODEL_GRACE_S = 0.5


class Commands:
    """Starts command turns and holds what they share. `hint` (the speech-to-text hint) and
    `roles` are replaced when the robot's tools change; `after_turn` runs after each turn's
    model work (the pipeline refreshes its view of the tools there)."""

    def __init__(
        self,
        config: PipelineConfig,
        assistant: Assistant,
        *,
        audio_native: bool,
        stt: Transcribing | None,
        turns: TurnTaking,
        speech: SpeechOutput,
        narrator: ProgressNarrator,
        motion: MotionWatch,
        stopper: StopController,
        answers: AnswerRecorder,
        floor: Floor,
        stats: PipelineStats,
        emit: Emit,
        after_turn: Callable[[], Awaitable[None]],
    ) -> None:
        self.config = config
        self.assistant = assistant
        self.audio_native = audio_native
        self.stt = stt
        self.turns = turns
        self.speech = speech
        self.narrator = narrator
        self.motion = motion
        self.stopper = stopper
        self.answers = answers
        self.floor = floor
        self.stats = stats
        self.emit = emit
        self.after_turn = after_turn
        self.hint = ""
        self.roles = VoiceRoles()
        self.wall_time: Callable[[float], float | None] = lambda _stream_s: None  # the pipeline's StreamAnchor

    def start(
        self, utt: HeardUtterance, verdict: Verdict, received: float, compute_s: float,
        speculation: Transcription | None,
    ) -> None:
        """A command turn for `utt`, taking the floor (whoever held it is cancelled)."""
        metrics = TurnMetrics(start=received)
        metrics.mark("endpoint", received + compute_s)
        metrics.speech_end = self.wall_time(last_word_end(utt.audio, utt.end))  # stream time -> clock
        turn = CommandTurn(self, self.floor.new_turn(), metrics)
        self.floor.take(turn.id, turn.run(utt, verdict, speculation), onset=utt.start)


class CommandTurn:
    """One command, from its utterance to the end of its speech (see the module docstring)."""

    def __init__(self, commands: Commands, turn_id: int, metrics: TurnMetrics) -> None:
        self._c = commands
        self.id = turn_id
        self.metrics = metrics
        self._calls: dict[str, ToolCalled] = {}  # by call id
        self._latest: dict[str, ToolCalled] = {}  # by tool name: progress reports carry no call id
        self._acks: dict[str, int | None] = {}  # call id -> speech handle of its acknowledgement
        self._moves: set[str] = set()  # call ids of motion tools under way
        self._heard = False  # something of this turn has been queued for speech

    async def _transcribe(
        self, audio: AudioChunk, utt: HeardUtterance, verdict: Verdict, speculation: Transcription | None
    ) -> tuple[Transcript, str, str | None]:
        """The command's transcript, its words (wake phrase removed) and why it is too unsure
        to act on (None: sure enough).

        An unsure transcript of a woken command whose speech began before the wake phrase is
        transcribed once more from just before the phrase. Talk in the same breath before the
        wake word (a television's last words) is transcribed with the command and weighs on
        the whole transcript's score: in the soak, "Breathe, hey Jarvis, call Anna." scored
        -0.65 and was turned away. The second run judges the command without it; a command
        buried in noise stays unsure. Only with speech before the phrase: a clean but cut-off
        "Hey Jarvis, video call" (-0.63) scored -0.55 on a second run of nearly the same
        audio, and was acted on."""
        c = self._c
        assert c.stt is not None
        heard = await c.stt.transcript_for(audio, self.metrics, speculation, c.hint)
        text, unsure = self._judged(heard, verdict)
        if unsure is not None and verdict.wake_at is not None and utt.start < verdict.wake_at - WAKE_PHRASE_S:
            tight = trim_to_wake(utt.audio, verdict.wake_at, WAKE_PHRASE_S)
            heard = await c.stt.transcript_for(tight, self.metrics, None, c.hint)
            text, unsure = self._judged(heard, verdict)
        return heard, text, unsure or too_noisy(utt.audio, c.config.confidence)

    def _judged(self, heard: Transcript, verdict: Verdict) -> tuple[str, str | None]:
        c = self._c
        text = strip_wake_words(heard.text, c.config.wake_phrase) if verdict.wake_at is not None else heard.text.strip()
        return restore(text, c.hint), unsure_reason(heard, text, c.config.confidence)

    async def run(self, utt: HeardUtterance, verdict: Verdict, speculation: Transcription | None) -> None:
        c = self._c
        metrics = self.metrics
        result: TurnResult | None = None
        started = cancelled = False
        try:
            audio = trim_to_wake(utt.audio, verdict.wake_at)
            content: str | tuple[ContentPart, ...]
            text = ""
            in_doubt = False  # a call that cannot be taken back is asked about first (assistant/confirm.py)
            if c.audio_native and (c.stt is None or utt.duration_s > c.config.turns.stop_max_s):
                if verdict.wake_at is not None and utt.end - verdict.wake_at < WAKE_ONLY_S:
                    c.turns.rearm(utt.end)
                    await report_ignored(c.emit, c.stats, "wake_only", utt)
                    return
                content = (AudioPart(wav_bytes(audio)),)
            else:
                heard, text, unsure = await self._transcribe(audio, utt, verdict, speculation)
                raw = heard.text
                await c.emit(TranscriptReady(text, metrics.stt_ms))
                if not verdict.wake_sure and not names_robot(raw, c.config.wake_phrase):
                    # an unsure wake word, and the words do not say the robot's name: talk, or,
                    # while the robot moves, a stop said without the wake word (`_stop_unaddressed`)
                    if not await self._stop_unaddressed(utt, raw):
                        await report_ignored(c.emit, c.stats, "wake_unconfirmed", utt, raw)
                    return
                if not re.search(r"[A-Za-z0-9]", text):
                    c.turns.rearm(utt.end)
                    await report_ignored(c.emit, c.stats, "wake_only" if verdict.wake_at is not None else "empty",
                                         utt, raw)
                    return
                if verdict.wake_at is not None and addressed_elsewhere(raw, c.config.wake_phrase):
                    # "Hey Charlie, …": the wake word fired on a near miss; not for the robot
                    await report_ignored(c.emit, c.stats, "addressed_elsewhere", utt, raw)
                    return
                # a stop acts before any doubt about the words, except when there is nothing to stop
                # (none made at a pause, the robot still): Whisper writes "Stop! Stop! Stop!" for
                # commands drowned in noise (audio v20)
                nothing_to_stop = c.motion.known_still and not c.stopper.stopped_for(utt.start)
                # unsure words with a stop as a clause of their own stop a robot that moves, and do
                # nothing else ("Stop right there, look after Smith Heiden" for "…, the cat's behind
                # you!": audio test v111 kept driving)
                if (is_stop_command(text) or (unsure is not None and says_stop(text))) \
                        and not (unsure is not None and nothing_to_stop):
                    c.assistant.confirmations.clear()  # a "stop" is no yes to "Shall I call Anna?"
                    if not await c.stopper.stop_once(utt.start, text, utt.end, metrics, self.id):
                        await report_ignored(c.emit, c.stats, "stopped_at_pause", utt, raw)  # at a pause
                    return
                if unsure is not None:
                    c.turns.rearm(utt.end)  # the person may say it again without the wake word
                    self._say(turned_away_with(unsure), "reply")
                    await report_ignored(c.emit, c.stats, unsure, utt, raw)
                    return
                content = (AudioPart(wav_bytes(audio)),) if c.audio_native else text
                in_doubt = doubtful(heard, c.config.confidence)
            mode: Literal["text", "audio"] = "audio" if isinstance(content, tuple) else "text"
            c.stats.turns += 1
            started = True
            c.turns.turn_started()
            await c.emit(VoiceTurnStarted(self.id, mode, text, audio.duration_s, verdict.follow_up))
            filler = asyncio.create_task(self._one_moment(), name=f"one-moment-{self.id}")
            try:
                result = await c.assistant.turn(content, metrics=metrics, observer=self.on_event, doubtful=in_doubt)
            finally:
                filler.cancel()
            c.answers.add(result)
            c.turns.turn_finished(asked_question=result.reply.rstrip().endswith("?"))
            self._end_motion()
            await c.after_turn()  # the tools may have changed during the turn
            await c.speech.idle(timeout=120.0)
        except asyncio.CancelledError:
            cancelled = True
            if started:
                c.turns.turn_cancelled()
            raise
        finally:
            self._end_motion()
            if started:
                await c.emit(VoiceTurnFinished(self.id, result, cancelled, metrics.as_dict()))
            c.answers.save(self.id)

    async def _stop_unaddressed(self, utt: HeardUtterance, raw: str) -> bool:
        """Stop for a short utterance heard while the robot moves that an unsure wake word made a
        command turn but whose words do not name the robot, when they say stop, as the stop check
        without the wake word would (`StopController.stop_if_said`): an unsure wake word never
        loses a stop. Whether it stopped."""
        c = self._c
        if not c.motion.moving or utt.duration_s > c.config.turns.stop_max_s:
            return False
        return await c.stopper.stop_if_said(utt, raw, self.metrics, self.id) is None

    def _end_motion(self) -> None:
        self._c.motion.forget(self._moves)
        self._moves.clear()

    def _say(self, text: str | None, kind: str) -> int | None:
        handle = self._c.speech.say(text, turn=self.id, kind=kind, metrics=self.metrics) if text else None
        self._heard = self._heard or handle is not None
        return handle

    async def _one_moment(self) -> None:
        """Say "One moment." if this turn would otherwise stay silent past `one_moment_after_s`
        from the end of the user's turn (a model still reading its prompt), and the model has had
        `MODEL_GRACE_S`. Marked ``one_moment`` in the metrics; ``first_audio`` stays the answer's."""
        speech = self._c.config.speech
        if not speech.one_moment:
            return
        now = self.metrics.clock()
        await asyncio.sleep(max(self.metrics.start + speech.one_moment_after_s - now, MODEL_GRACE_S))
        if not self._heard:
            self._heard = True
            self.metrics.mark("one_moment")
            self._c.speech.say(speech.one_moment, turn=self.id, kind="wait")

    async def on_event(self, event: TurnEvent) -> None:
        """This turn's observer of the assistant: what it produces goes to speech."""
        c = self._c
        now = time.monotonic()
        match event:
            case SentenceReady(text):
                self._say(text, "reply")
            case ToolCalled(call_id, name, arguments):
                self._calls[call_id] = self._latest[name] = event
                if name in c.roles.motion:
                    self._moves.add(call_id)
                    c.motion.started(call_id)
                self._acks[call_id] = self._say(c.narrator.on_call(name, arguments, now), "progress")
            case ToolProgressed(name, progress, total, message):
                called = self._latest.get(name)
                line = c.narrator.on_progress(name, progress, total, message, now,
                                              called.arguments if called is not None else None)
                self._say(line, "progress")
            case ToolReturned(call_id=call_id, is_error=failed):
                self._moves.discard(call_id)
                c.motion.finished(call_id)
                ack = self._acks.pop(call_id, None)
                if failed:
                    c.speech.withdraw(ack)  # "On my way ..." not yet said: the tool failed at once
                # its success/failure phrase, if any, is the turn's answer (assistant.phrase)
            case _:
                pass
        await c.emit(event)
