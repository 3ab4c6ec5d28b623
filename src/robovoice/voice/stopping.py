"""The spoken stop (DESIGN.md §8): the robot's stop tool, called directly, never behind the model.

`StopController.check` is a stop check: a short utterance heard without the wake word while
the robot moves, transcribed with the stop words as the hint and matched against the stop
grammar (`stop.says_stop`). `check_pause` makes the same check on the speculative
transcript at the first pause of any short utterance while the robot moves, addressed or not,
so a stop acts without waiting for the end-of-turn silence (whatever follows a "stop" cannot
make stopping wrong); a stop is made once per utterance, by whichever check gets there first.
For an addressed utterance the rest is not lost: "Hey Jarvis, stop there, and then go back to
your charger" stops at the pause, and the whole transcript still goes to the model as a
command turn, which this stop does not cancel; the robot says "Stopped." only once the person
has finished that utterance (`utterance_ended`), so it never talks over them and its own
words do not end up in their transcript. `StopController.stop` stops the robot: it cancels the turn
holding the floor (and the action it started), drops queued speech, calls the tool with the
``stop`` role (`roles.VoiceRoles.stop`, from the robot's manifests) with a bounded wait, and
says the outcome. It runs beside a turn, never inside the model's loop.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
from collections.abc import Callable

from robovoice.assistant.events import ToolCalled, ToolReturned
from robovoice.assistant.loop import TurnResult
from robovoice.assistant.metrics import TurnMetrics
from robovoice.assistant.robot_tools import Toolbox
from robovoice.manifest.voice import fill
from robovoice.voice.answers import AnswerRecorder
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import Emit, RobotStopped, StopHeard
from robovoice.voice.floor import Floor, PipelineStats, report_ignored
from robovoice.voice.lastword import last_word_end
from robovoice.voice.listener import HeardPause, HeardUtterance
from robovoice.voice.roles import VoiceRoles
from robovoice.voice.speech import SpeechOutput
from robovoice.voice.stop import says_stop
from robovoice.voice.utterance import OwnWords, Transcribing, Transcription, strip_wake_words
from robovoice.voice.vocabulary import STOP_HINT

log = logging.getLogger(__name__)


class StopController:
    """See the module docstring. `roles` is replaced when the robot's tools change."""

    def __init__(
        self,
        config: PipelineConfig,
        tools: Toolbox,
        *,
        speech: SpeechOutput,
        floor: Floor,
        answers: AnswerRecorder,
        stats: PipelineStats,
        emit: Emit,
        stt: Transcribing | None,
        own_words: OwnWords,
    ) -> None:
        self.config = config
        self.tools = tools
        self.speech = speech
        self.floor = floor
        self.answers = answers
        self.stats = stats
        self.emit = emit
        self.stt = stt
        self.own_words = own_words
        self.roles = VoiceRoles()
        self.wall_time: Callable[[float], float | None] = lambda _stream_s: None  # the pipeline's clock mapping
        self._stopped_for: float | None = None  # the onset of the utterance the last stop was made for
        self._ended: float | None = None  # the onset of the last utterance the listener closed
        self._end = asyncio.Event()

    def utterance_ended(self, onset: float) -> None:
        """The router: the utterance that started at `onset` is over."""
        self._ended = onset
        self._end.set()

    async def _after_utterance(self, onset: float) -> None:
        """Until the utterance that started at `onset` is over (at most the longest utterance)."""
        with contextlib.suppress(TimeoutError):
            async with asyncio.timeout(self.config.endpointer.max_utterance_s):
                while self._ended is None or self._ended < onset:
                    self._end.clear()
                    await self._end.wait()

    def stopped_for(self, onset: float) -> bool:
        """Whether a stop was made for the utterance starting at `onset` (at one of its pauses)."""
        return self._stopped_for == onset

    async def stop_once(self, onset: float, text: str, at: float, metrics: TurnMetrics,
                        turn: int | None = None, *, at_pause: bool = False) -> bool:
        """Stop for the utterance starting at `onset`, unless a stop was already made for it
        (its pauses and its end may each find the stop); whether it stopped now. `turn`: the
        command turn it is made in (None: a turn of its own, whose answers are saved here);
        `at_pause`: the utterance may still go on (its reply waits for its end)."""
        if self.stopped_for(onset):
            return False
        self._stopped_for = onset
        if turn is not None:
            await self.stop(text, at, turn, metrics, spare=onset)
            return True
        turn = self.floor.new_turn()
        try:
            await self.stop(text, at, turn, metrics, spare=onset, at_pause=at_pause)
        finally:
            self.answers.save(turn)
        return True

    async def check_pause(self, pause: HeardPause, transcription: Transcription, received: float) -> None:
        """A stop said and paused after, the robot moving: stop at once from the speculative
        transcript. Words the robot itself says are left to `check`, which knows how much of the
        utterance was its own playback."""
        metrics = TurnMetrics(start=received)
        metrics.speech_end = self.wall_time(last_word_end(pause.audio, pause.at))
        await asyncio.wait([transcription])  # its cancellation (speech went on) is not ours
        if transcription.cancelled() or transcription.exception() is not None:
            return
        transcript, took_ms = transcription.result()
        text = transcript.text
        if not says_stop(strip_wake_words(text, self.config.wake_phrase)) or self.own_words.contains(text) \
                or self._misheard_own(pause.playback_share, pause.near_end, text):
            return
        metrics.stt_ms += took_ms
        metrics.mark("transcript")
        log.info("stop heard at the first pause (%.2f s), before the end of the utterance", pause.at)
        await self.stop_once(pause.onset, text, pause.at, metrics, at_pause=True)

    async def check(self, utt: HeardUtterance, received: float, speculation: Transcription | None) -> None:
        """Is this short utterance (no wake word, the robot moving) a stop? Then stop."""
        metrics = TurnMetrics(start=received)
        metrics.speech_end = self.wall_time(last_word_end(utt.audio, utt.end))  # the stop's last word
        if self.stt is None:
            await report_ignored(self.emit, self.stats, "no_stt_for_stop_check", utt)
            return
        text = await self.stt.text_for(utt.audio, metrics, speculation, STOP_HINT)
        if (why := await self.stop_if_said(utt, text, metrics)) is not None:
            await report_ignored(self.emit, self.stats, why, utt, text)

    async def stop_if_said(self, utt: HeardUtterance, text: str, metrics: TurnMetrics,
                           turn: int | None = None) -> str | None:
        """Stop for `utt` when its transcript `text` says stop (`says_stop`, the wake phrase
        removed) and is not the robot's own voice heard back: None when it did (here, or already
        at a pause), else why not ("not_a_stop", "own_voice"). `turn`: as for `stop_once`."""
        if not says_stop(strip_wake_words(text, self.config.wake_phrase)):
            return "not_a_stop"
        if (utt.playback_share > 0.3 and self.own_words.contains(text)) \
                or self._misheard_own(utt.playback_share, utt.near_end, text):
            return "own_voice"  # the robot heard itself, in its words or misheard
        if not await self.stop_once(utt.start, text, utt.end, metrics, turn):
            await report_ignored(self.emit, self.stats, "stopped_at_pause", utt, text)  # `check_pause` did
        return None

    def _misheard_own(self, playback_share: float, near_end: bool, text: str) -> bool:
        """The robot's own voice, misheard as a stop ("Alright, hold on." for its "All right, I
        won't.", audio test v52, during a drive): heard mostly while it played, no louder than its
        echo, and reading like what it said. A person's "stop" over its voice fails at least one."""
        return playback_share > 0.5 and not near_end and self.own_words.resembles(text)

    async def stop(self, text: str, at: float, turn: int, metrics: TurnMetrics, spare: float | None = None,
                   at_pause: bool = False) -> None:
        """Stop the robot now: the stop tool, straight; the active turn cancelled (unless it
        answers the utterance that started at `spare`: the one this stop was heard in); no model.
        `at_pause`: the outcome is said once that utterance is over."""
        self.stats.stops += 1
        tool = self.roles.stop
        cancelled = self.floor.cancel_active(spare)
        self.speech.interrupt()
        await self.emit(StopHeard(text, at, cancelled, tool))
        called = ToolCalled(f"local-stop-{turn}", tool or "", {})
        result = None
        started = time.perf_counter()
        if tool is None:
            ok, detail = False, "the robot declares no stop tool"
        else:
            metrics.mark(f"tool_call:{tool}")
            try:
                async with asyncio.timeout(self.config.stop_timeout_s):
                    outcome = await self.tools.call(tool, {})
                ok, detail, result = not outcome.is_error, outcome.text, outcome.structured
            except TimeoutError:
                ok, detail = False, f"the stop tool did not answer within {self.config.stop_timeout_s:g} s"
        took_ms = (time.perf_counter() - started) * 1000.0
        metrics.tools_ms += took_ms
        metrics.mark(f"tool_result:{tool or 'none'}")
        log.info("spoken stop: %s (%s)", "robot stopped" if ok else "STOP FAILED", detail)
        from_word = metrics.from_speech_end().get(f"tool_result:{tool or 'none'}")
        await self.emit(RobotStopped(ok, detail, metrics.marks[f"tool_result:{tool or 'none'}"], from_word))
        phrases = self.roles.say(tool) if tool else None
        fields = result if isinstance(result, dict) else {}
        if ok:
            reply = fill(phrases.success if phrases else None, fields) or self.config.speech.stop_reply
        else:
            reply = fill(phrases.failure if phrases else None, fields) or self.config.speech.stop_failed_reply
        if at_pause and spare is not None:
            await self._after_utterance(spare)
        self.speech.say(reply, turn=turn, kind="stop", metrics=metrics)
        error = None if ok else (fields.get("error") if isinstance(fields.get("error"), str) else "stop_failed")
        returned = ToolReturned(called.call_id, called.name, detail, not ok, took_ms, error,
                                fields if result is not None else None)
        self.answers.add(TurnResult(reply, (called,) if tool else (), (returned,) if tool else (), metrics))
        await self.speech.idle(timeout=30.0)
