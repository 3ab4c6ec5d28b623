"""What was heard, and what it becomes: the listener's facts routed to turn-taking, command
turns, stop checks and speculative speech-to-text.

`Router.handle` runs inside the microphone loop, so it never waits on the network or on a
model: it decides from what is known now (turn-taking state, `MotionWatch.moving`, which
answers at once) and hands anything slow to a task of the pipeline's TaskGroup (`Floor`).

- wake word: heard during the robot's own playback -> rejected; while the robot is busy ->
  barge-in (speech dropped, the active turn cancelled); then turn-taking is told. An unsure
  wake word (a score under the threshold) is only passed on while the robot is idle and a
  transcript will be made: the command turn checks that it names the robot (and, while the
  robot moves, takes words that do not for a stop check);
- speech starts or pauses: the motion watch is asked to refresh (for a stop without the
  wake word); at a pause of an utterance that will need it, transcription starts speculatively,
  and its transcript may shorten the end-of-turn silence and prefill the model
  (`speculate.Speculator`); while the robot moves, a stop said before a short utterance's
  first pause acts there (`StopController.check_pause`), with or without the wake word;
- an utterance ends: a command turn (`command.Commands`), a stop check
  (`stopping.StopController`), or ignored with a reason.
"""

from __future__ import annotations

import logging

from robovoice.voice.command import Commands
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import BargedIn, Emit, WakeWordHeard, WakeWordRejected
from robovoice.voice.floor import Floor, PipelineStats, report_ignored
from robovoice.voice.listener import Heard, HeardPause, HeardSpeechStart, HeardUtterance, HeardWake
from robovoice.voice.motion import MotionWatch
from robovoice.voice.speculate import SpeculationConfig, Speculator
from robovoice.voice.speech import SpeechOutput
from robovoice.voice.stopping import StopController
from robovoice.voice.turns import Action, TurnTaking
from robovoice.voice.utterance import Transcribing, trim_to_wake
from robovoice.voice.vocabulary import STOP_HINT

log = logging.getLogger(__name__)


class Router:
    """See the module docstring."""

    def __init__(
        self,
        config: PipelineConfig,
        *,
        audio_native: bool,
        stt: Transcribing | None,
        turns: TurnTaking,
        speech: SpeechOutput,
        motion: MotionWatch,
        commands: Commands,
        stopper: StopController,
        floor: Floor,
        stats: PipelineStats,
        emit: Emit,
        speculation: SpeculationConfig | None = None,
    ) -> None:
        self.config = config
        self.audio_native = audio_native
        self.stt = stt
        self.turns = turns
        self.speech = speech
        self.motion = motion
        self.commands = commands
        self.stopper = stopper
        self.floor = floor
        self.stats = stats
        self.emit = emit
        self.speculator = Speculator(speculation or config.speculation, commands.assistant, config.wake_phrase)
        self._speaking_since: float | None = None  # the onset of the utterance in progress

    async def handle(self, heard: Heard, received: float) -> None:
        """What the listener heard in one chunk; `received`: when the chunk arrived."""
        self.stats.frontend_s += heard.compute_s
        self.stats.frontend_cpu_s += heard.cpu_s
        self.turns.playback(heard.playing or self.speech.busy, heard.now)
        if self.turns.expire(heard.now, self._speaking_since):
            log.info("wake word not followed by a command; listening again")
        for event in heard.events:
            match event:
                case HeardWake():
                    await self._on_wake(event)
                case HeardSpeechStart():
                    self._speaking_since = event.at
                    self.motion.want()
                case HeardPause():
                    self.motion.want()
                    self._on_pause(event, received)
                case HeardUtterance():
                    self._speaking_since = None
                    await self._on_utterance(event, received, heard.compute_s)
        self.floor.changed.set()

    async def _on_wake(self, event: HeardWake) -> None:
        if not event.sure and (self.stt is None or self.audio_native or self.floor.busy or self.speech.busy):
            # (while the robot moves it is passed on: a command turn whose words do not name the
            # robot is still checked for a stop there, as it would be without the wake word)
            log.info("unsure wake word (%.2f) at %.2f s ignored: no transcript to check it, or the robot is busy",
                     event.score, event.at)
            return
        if not event.near_end:
            self.stats.rejected_wakes += 1
            log.info("wake word at %.2f s rejected: the robot's own playback", event.at)
            await self.emit(WakeWordRejected(event.score, event.at))
            return
        if self.floor.busy or self.speech.busy:
            self.stats.barge_ins += 1
            cancelled = self.floor.cancel_active()
            self.speech.interrupt()
            await self.emit(BargedIn(event.at, cancelled))
        self.turns.wake(event.at, sure=event.sure)
        await self.emit(WakeWordHeard(event.score, event.at, event.during_playback, event.sure))

    def _on_pause(self, pause: HeardPause, received: float) -> None:
        """Start transcribing at the first pause of an utterance that will need it, so the
        transcript is (nearly) ready when the end-of-turn silence confirms the end."""
        if self.stt is None or not self.floor.running:
            return
        short = pause.at - pause.onset <= self.config.turns.stop_max_s
        addressed = self.turns.addressed(pause.onset, pause.at)
        if self.audio_native and not (addressed and short):
            return  # audio goes to the model as it is; only short commands are checked for a stop
        if not addressed and not (self.motion.moving and short):
            return
        floor = self.floor
        transcription = self.stt.speculate(pause.onset, pause.at, trim_to_wake(pause.audio, self.turns.pending_wake),
                                           lambda coro: floor.spawn(coro, "voice-stt-speculative"),
                                           self.commands.hint if addressed else STOP_HINT)
        woken = addressed and self.turns.pending_wake is not None
        command = addressed and not self.audio_native
        floor.spawn(self.speculator.follow(pause, transcription, woken=woken, command=command), "voice-speculation")
        if self.motion.moving and short:  # a stop acts at the first pause, addressed or not
            floor.check(self.stopper.check_pause(pause, transcription, received))

    async def _on_utterance(self, utt: HeardUtterance, received: float, compute_s: float) -> None:
        self.stopper.utterance_ended(utt.start)  # a stop made at its pause may say so now
        short = utt.duration_s <= self.config.turns.stop_max_s
        moving = short and not self.turns.addressed(utt.start, utt.end) and self.motion.moving
        verdict = self.turns.classify(utt.start, utt.end, moving=moving)
        own_voice = utt.playback_share > 0.5 and not utt.near_end
        hint = STOP_HINT if verdict.action is Action.STOP_CHECK else self.commands.hint
        speculation = self.stt.take(utt.start, utt.end, hint) if self.stt is not None else None
        heard_wake = verdict.wake_at is not None and not verdict.rearmed  # a wake word said now
        if verdict.action is Action.COMMAND and (heard_wake or not own_voice):
            self.commands.start(utt, verdict, received, compute_s, speculation)
        elif verdict.action is Action.STOP_CHECK:
            # no acoustic gate here: a missed stop is worse than a needless one, and the robot's
            # own "stop" is recognised by its words (`OwnWords`) instead
            self.floor.check(self.stopper.check(utt, received, speculation))
        else:
            if speculation is not None:
                speculation.cancel()
            if verdict.rearmed and verdict.wake_at is not None:
                self.turns.rearm(verdict.wake_at)  # its own voice does not use up the wait for the words
            await report_ignored(self.emit, self.stats, "own_voice" if own_voice else verdict.reason or "no_wake_word",
                                 utt)
