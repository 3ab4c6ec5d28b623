"""The always-on listener: echo cancellation, wake word and VAD over 80 ms frames.

`Listener.process(chunk)` is blocking (it runs the models) and is called on the
listener's own executor. Per 80 ms frame of 16 kHz microphone audio it

1. cancels the robot's own playback (`echo.EchoCanceller` against `PlaybackReference`),
2. raises the wake threshold while anything plays (robot speech, a call's remote voice),
3. runs the wake word spotter and the VAD segmenter on the cleaned signal,
4. while something plays, also scores the *playback itself* with a second wake word
   detector: a wake word heard on the microphone while the playback said it (the robot's
   own "Hey Jarvis", or a remote caller's) is the robot's own voice and is rejected,
   however well or badly the echo canceller has converged (a wake the playback has not
   matched yet waits `PLAYBACK_MATCH_WAIT_S` for its next scores: either may fire first);
5. judges every utterance that overlaps playback with `EchoMeter`: is it the person
   (louder than what the echo canceller leaves) or what is left of the robot's own voice?

It returns `Heard` results carrying the verdicts; all decisions about turns are the
pipeline's (`turns.TurnTaking`).
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, Framer, as_float32, float32_to_int16
from robovoice.audio.vad import SpeechEnded, SpeechSegmenter, SpeechStarted
from robovoice.audio.wake import WakeWordDetector, WakeWordSpotter
from robovoice.errors import AudioError
from robovoice.voice.config import EchoConfig
from robovoice.voice.echo import BlockStats, EchoCanceller, PlaybackReference

log = logging.getLogger(__name__)

FRAME_SAMPLES = 1280  # 80 ms: one wake word frame, five echo canceller blocks
# How far back a wake word detection reaches: the phrase (~1 s) and the detector's latency. A
# detection at t is about audio from t - WAKE_WINDOW_S on, so it counts as said during playback
# when anything played in that window, even if the playback (a sentence ending in "Hey Jarvis",
# the next one not yet synthesised) stopped before the detector fired.
WAKE_WINDOW_S = 1.2
# The microphone's detector and the playback's cross their thresholds within a frame or two of
# each other, either first: a wake heard during playback that the playback has not (yet) matched
# waits this long for the playback's next scores before it counts as the person's.
PLAYBACK_MATCH_WAIT_S = 0.16
_REF_ACTIVE = 1e-8  # reference power above which the speaker counts as playing (-80 dBFS)


@dataclass(frozen=True, slots=True)
class HeardWake:
    score: float
    at: float
    during_playback: bool
    near_end: bool  # false: the robot's own playback, not the person
    playback_score: float = 0.0  # the playback's own wake score around `at`
    sure: bool = True  # false: under the wake threshold; it counts only if the transcript names the robot


@dataclass(frozen=True, slots=True)
class HeardSpeechStart:
    at: float


@dataclass(frozen=True, slots=True)
class HeardPause:
    """Speech went quiet at `at` after starting at `onset`: the utterance may be over (the
    end of turn is confirmed only after the end-of-turn silence). `audio` is the utterance
    so far, so speech-to-text can start now, speculatively, inside that silence.
    `end_early(silence_s)`: let this pause end the utterance after only `silence_s` of silence
    (when the words up to it form a complete request) unless speech resumes; callable from
    the event loop (`Endpointer.allow_early_end`)."""

    onset: float
    at: float
    audio: AudioChunk
    end_early: Callable[[float], None] = field(default=lambda _silence_s: None, compare=False, repr=False)
    playback_share: float = 0.0  # as for `HeardUtterance`, over the utterance so far
    near_end: bool = True


@dataclass(frozen=True, slots=True)
class HeardUtterance:
    """A VAD utterance (echo-cancelled 16 kHz audio with pre-roll), and whether it came
    while something played (`playback_share`: fraction of its time) and is louder than
    the echo that is left (`near_end`)."""

    audio: AudioChunk
    start: float
    end: float
    truncated: bool
    playback_share: float
    near_end: bool
    early: bool = False  # ended on a pause's shorter silence (`HeardPause.end_early`)

    @property
    def duration_s(self) -> float:
        return self.end - self.start


HeardEvent = HeardWake | HeardSpeechStart | HeardPause | HeardUtterance


@dataclass(frozen=True, slots=True)
class Heard:
    """What the listener heard in one chunk (or at the end of the stream)."""

    events: tuple[HeardEvent, ...]
    now: float  # stream time at the end of the processed audio
    playing: bool  # playback (or its tail) at `now`
    compute_s: float  # wall time spent
    cpu_s: float = 0.0  # CPU time spent (this thread)


class EchoMeter:
    """Remembers the echo canceller's block levels for the last seconds and judges windows.

    The *leak* is how much of the echo the canceller leaves: residual over microphone
    power, summed over the blocks with playback in the `leak_window_s` seconds before the
    window judged (while the canceller converges this is high, once converged low). A window heard during playback
    is the person's when its own residual/microphone ratio exceeds the leak by
    `margin_db`: talk over the robot raises the residual far above the leak; the robot's
    own voice leaves it at the leak. Before enough blocks were seen the leak is taken as 1
    (no cancellation assumed): nothing then counts as the person.
    """

    def __init__(self, *, margin_db: float = 6.0, history_s: float = 40.0, leak_window_s: float = 30.0) -> None:
        self.margin = 10 ** (margin_db / 10)
        self._blocks: deque[tuple[float, BlockStats]] = deque()
        self._history_s = history_s
        self._leak_window_s = leak_window_s

    def add(self, t: float, stats: BlockStats) -> None:
        self._blocks.append((t, stats))
        while self._blocks and t - self._blocks[0][0] > self._history_s:
            self._blocks.popleft()

    def leak(self, before: float) -> float:
        """The leak measured on the playback of the `leak_window_s` seconds before `before`."""
        residual = mic = 0.0
        count = 0
        for t, s in self._blocks:
            if before - self._leak_window_s <= t < before and s.reference > _REF_ACTIVE and s.mic > 1e-7:
                residual += s.residual
                mic += s.mic
                count += 1
        return residual / mic if count >= 25 else 1.0

    def judge(self, start: float, end: float) -> tuple[float, bool]:
        """(share of the window with playback, whether the person is audible over the echo).
        The leak is measured before the window, so talk inside it cannot hide itself."""
        inside = [s for t, s in self._blocks if start - 0.016 <= t <= end]
        if not inside:
            return 0.0, True
        playing = [s for s in inside if s.reference > _REF_ACTIVE]
        share = len(playing) / len(inside)
        if not playing:
            return share, True
        residual = sum(s.residual for s in playing)
        mic = sum(s.mic for s in playing) + 1e-12
        return share, residual / mic > self.leak(start - 0.016) * self.margin


class Listener:
    """Echo cancellation + wake word + VAD for one microphone stream (see module docstring)."""

    def __init__(
        self,
        spotter: WakeWordSpotter,
        segmenter: SpeechSegmenter,
        reference: PlaybackReference | None,
        echo: EchoConfig,
        *,
        playback_detector: WakeWordDetector | None = None,
        playback_tail_s: float,
    ) -> None:
        self.spotter = spotter
        self.segmenter = segmenter
        self.reference = reference
        self._playback_detector = playback_detector if reference is not None else None
        self._playback_scores: deque[tuple[float, float]] = deque()
        self._playback_idle_frames = 0
        self._unmatched: list[HeardWake] = []  # wakes during playback waiting for its later scores
        self.config = echo
        self._aec = (
            EchoCanceller(partitions=self.config.partitions, step=self.config.step)
            if reference is not None and self.config.enabled
            else None
        )
        self.meter = EchoMeter(margin_db=self.config.near_end_margin_db)
        self._framer = Framer(FRAME_SAMPLES)
        self._tail = playback_tail_s
        self._last_playback = -math.inf
        self.external_playback = False  # e.g. a call's remote voice played outside this pipeline
        self.now = 0.0
        self._recent: deque[AudioChunk] = deque()  # cleaned audio of the current utterance + pre-roll
        self._onset: float | None = None
        self._paused = False

    def reset(self) -> None:
        """Fresh state for an independent stream (a new evaluation clip)."""
        self.spotter.reset()
        self.segmenter.reset()
        self._framer.reset()
        if self._aec is not None:
            self._aec.reset()
        self.meter = EchoMeter(margin_db=self.config.near_end_margin_db)
        self._last_playback = -math.inf
        self._recent.clear()
        self._onset = None
        self._paused = False
        self._playback_scores.clear()
        self._unmatched.clear()
        if self._playback_detector is not None:
            self._playback_detector.reset()

    def playing_at(self, t: float) -> bool:
        return self.external_playback or t - self._last_playback <= self._tail

    def _playing_during(self, start: float, end: float) -> bool:
        """Playback (or its echo tail) sounded at some moment from `start` to `end`."""
        return self.playing_at(end) or self._last_playback >= start - self._tail

    def process(self, chunk: AudioChunk) -> Heard:
        """Blocking: run every complete 80 ms frame of `chunk` (16 kHz mono)."""
        if chunk.format.rate != MODEL_FORMAT.rate or chunk.format.channels != 1:
            raise AudioError(f"the listener takes 16 kHz mono audio, got {chunk.format}")
        started, cpu = time.perf_counter(), time.thread_time()
        events: list[HeardEvent] = []
        for frame in self._framer.push(chunk):
            events.extend(self._frame(frame))
        self.now = chunk.end_timestamp
        return Heard(tuple(events), self.now, self.playing_at(self.now), time.perf_counter() - started,
                              time.thread_time() - cpu)

    def flush(self) -> Heard:
        """End of the stream: close an utterance in progress."""
        events: list[HeardEvent] = self._matched(self.now, final=True)
        for event in self.segmenter.flush():
            if isinstance(event, SpeechEnded):
                events.append(self._utterance(event))
        return Heard(tuple(events), self.now, False, 0.0)

    def _frame(self, frame: AudioChunk) -> list[HeardEvent]:
        t0, t1 = frame.timestamp, frame.end_timestamp
        cleaned = frame
        if self.reference is not None:
            ref = self.reference.window(t0, FRAME_SAMPLES)
            self._score_playback(ref, t1)
            if self._aec is not None:
                out, stats = self._aec.process(as_float32(frame.samples), ref)
                block_s = self._aec.block / MODEL_FORMAT.rate
                for i, s in enumerate(stats):
                    self.meter.add(t0 + (i + 1) * block_s, s)
                    if s.reference > _REF_ACTIVE:
                        self._last_playback = t0 + (i + 1) * block_s
                cleaned = AudioChunk(float32_to_int16(out), MODEL_FORMAT, t0)
            elif float(np.mean(ref * ref)) > _REF_ACTIVE:
                self._last_playback = t1
        # the raised threshold holds while the audio the detector scores holds playback
        playing = self._playing_during(t1 - WAKE_WINDOW_S, t1)
        self.spotter.decider.set_threshold(self.config.playback_wake_threshold if playing else None)
        events: list[HeardEvent] = self._matched(t1)
        for wake in self.spotter.feed(cleaned):
            during = self._playing_during(wake.timestamp - WAKE_WINDOW_S, wake.timestamp)
            if during and not wake.sure:
                continue  # an unsure score around playback is as likely the robot's own voice
            near, own = True, 0.0
            if during:
                own = self._playback_score(wake.timestamp)
                if self._playback_detector is not None:
                    near = own < self.config.playback_match_score
                    if near:  # not matched yet: the playback's next frames decide
                        self._unmatched.append(HeardWake(wake.score, wake.timestamp, during, near, own))
                        continue
                else:  # no detector on the playback: fall back on the echo levels
                    _, near = self.meter.judge(wake.timestamp - 1.0, wake.timestamp)
            events.append(HeardWake(wake.score, wake.timestamp, during, near, own, wake.sure))
        self._remember(cleaned)
        for vad_event in self.segmenter.feed(cleaned):
            if isinstance(vad_event, SpeechStarted):
                self._onset, self._paused = vad_event.timestamp, False
                events.append(HeardSpeechStart(vad_event.timestamp))
            else:
                self._onset = None
                events.append(self._utterance(vad_event))
        pause = self._pause(t1)
        if pause is not None:
            events.append(pause)
        return events

    def _remember(self, frame: AudioChunk) -> None:
        keep_s = self.segmenter.endpointer.config.max_utterance_s + 1.0
        self._recent.append(frame)
        while self._recent and frame.end_timestamp - self._recent[0].timestamp > keep_s:
            self._recent.popleft()

    def _pause(self, now: float) -> HeardPause | None:
        """A `HeardPause` on the first quiet frame of an utterance in progress."""
        endpointer = self.segmenter.endpointer
        if self._onset is None or not endpointer.in_speech:
            return None
        quiet = self.segmenter.last_probability < endpointer.config.stop_threshold
        if not quiet:
            self._paused = False
            return None
        if self._paused:
            return None
        self._paused = True
        start = self._onset - endpointer.config.pre_roll_s
        frames = [f for f in self._recent if f.end_timestamp > start]
        if not frames:
            return None
        audio = AudioChunk(np.concatenate([f.samples for f in frames]), MODEL_FORMAT, frames[0].timestamp)
        onset = self._onset

        def end_early(silence_s: float) -> None:
            endpointer.allow_early_end(onset, now, silence_s)

        share, near = self.meter.judge(onset, now)
        return HeardPause(onset, now, audio, end_early, share, near)

    def _score_playback(self, ref: np.ndarray, t1: float) -> None:
        """Run the playback through its own wake word detector while anything plays."""
        detector = self._playback_detector
        if detector is None:
            return
        active = float(np.mean(ref * ref)) > _REF_ACTIVE
        if not active:
            self._playback_idle_frames += 1
            if self._playback_idle_frames * FRAME_SAMPLES / MODEL_FORMAT.rate > 2.0:
                return  # long silent: nothing to score (reset when playback resumes)
        else:
            if self._playback_idle_frames * FRAME_SAMPLES / MODEL_FORMAT.rate > 2.0:
                detector.reset()
            self._playback_idle_frames = 0
        score = detector.process(float32_to_int16(ref))
        self._playback_scores.append((t1, score))
        while self._playback_scores and t1 - self._playback_scores[0][0] > 3.0:
            self._playback_scores.popleft()

    def _playback_score(self, at: float) -> float:
        """The playback's highest wake score in the wake window up to `at` and the wait after it."""
        return max((s for t, s in self._playback_scores if at - WAKE_WINDOW_S <= t <= at + PLAYBACK_MATCH_WAIT_S),
                   default=0.0)

    def _matched(self, now: float, *, final: bool = False) -> list[HeardEvent]:
        """The waiting wakes whose wait is over at `now` (all of them when `final`), judged again
        with the playback's scores since: the person's, or the playback's after all."""
        done = [w for w in self._unmatched if final or now >= w.at + PLAYBACK_MATCH_WAIT_S]
        self._unmatched = [w for w in self._unmatched if w not in done]
        events: list[HeardEvent] = []
        for wake in done:
            own = self._playback_score(wake.at)
            events.append(dataclasses.replace(wake, near_end=own < self.config.playback_match_score,
                                              playback_score=own))
        return events

    def _utterance(self, ended: SpeechEnded) -> HeardUtterance:
        share, near = self.meter.judge(ended.start, ended.end)
        if self.external_playback:  # played outside this pipeline: no reference to judge by
            share = 1.0
        return HeardUtterance(ended.audio, ended.start, ended.end, ended.truncated, share, near, ended.early)
