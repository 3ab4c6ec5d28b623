"""A simulated room: the headless microphone and speaker of a robot, for tests and the demo.

`SimulatedRoom` produces what the robot's microphone would pick up, paced like a real
device (`speed` x real time): the person's speech (`say`), optional background noise, and
the **echo of whatever the robot's speaker plays** — its own speech (`speaker`, the
pipeline's `AudioSink`) and a video call's remote participant (`play_remote`) — through an
echo path of delay, gain and a few reflections (`EchoPath`). Everything played is also
written to the `PlaybackReference` at the moment it sounds, as a real playback path would,
so echo cancellation can be tested against exactly the signal a robot would have.

Time is the room's stream time in seconds (chunk timestamps), starting at `start`. A paced
room's stream time is tied to the event loop's clock: stream time `start + t` is captured at
wall time ``wall0 + t / speed`` (a chunk is delivered once its last sample is due, like a sound
card's buffer). The robot's speech starts sounding no earlier than the stream position of the
moment it reaches the speaker (`RoomSpeaker.write`), so latencies read off `played` (or a
session recording, `voice.recording`) are the ones the pipeline's clock sees.
"""

from __future__ import annotations

import asyncio
import logging
import math
import time
from collections import deque
from collections.abc import AsyncIterator
from dataclasses import dataclass, field

import numpy as np

from robovoice.audio.format import (
    MODEL_FORMAT,
    AudioChunk,
    AudioFormat,
    Float32Array,
    as_float32,
    concat,
    convert,
    float32_to_int16,
)
from robovoice.errors import AudioError
from robovoice.voice.echo import PlaybackReference

log = logging.getLogger(__name__)

RATE = MODEL_FORMAT.rate
_F32 = MODEL_FORMAT.with_(width=4)


@dataclass(frozen=True, slots=True)
class EchoPath:
    """Speaker -> microphone: direct path after `delay_s` at `gain_db`, plus reflections
    (delay after the direct path in s, level relative to it in dB)."""

    gain_db: float = -6.0
    delay_s: float = 0.006
    reflections: tuple[tuple[float, float], ...] = ((0.004, -9.0), (0.011, -12.0), (0.023, -16.0), (0.041, -22.0))

    def taps(self) -> list[tuple[int, float]]:
        g = 10 ** (self.gain_db / 20)
        d = round(self.delay_s * RATE)
        out = [(d, g)]
        out += [(d + round(dt * RATE), g * 10 ** (db / 20)) for dt, db in self.reflections]
        return out

    @property
    def length(self) -> int:
        return max(i for i, _ in self.taps()) + 1


@dataclass(slots=True)
class Speech:
    """Audio scheduled in the room: where it sounds (stream time) and when it is over."""

    start: float
    end: float
    done: asyncio.Event = field(default_factory=asyncio.Event)

    async def finished(self, timeout: float = 60.0) -> None:
        async with asyncio.timeout(timeout):
            await self.done.wait()


class SimulatedRoom:
    """See the module docstring. Use `mic` as the pipeline's source and `speaker` as its sink."""

    def __init__(
        self,
        reference: PlaybackReference | None = None,
        *,
        speed: float = 1.0,
        chunk_s: float = 0.08,
        echo: EchoPath | None = EchoPath(),
        noise: AudioChunk | None = None,
        noise_gain: float = 1.0,
        start: float = 0.0,
        record: bool = False,
    ) -> None:
        if speed <= 0:
            raise AudioError(f"room speed must be positive, got {speed}")
        self.reference = reference if reference is not None else PlaybackReference()
        self.speed = speed
        self.chunk_frames = round(chunk_s * RATE)
        self.echo = echo
        self._taps = echo.taps() if echo is not None else []
        self._echo_len = echo.length if echo is not None else 0
        self._noise = as_float32(convert(noise, _F32).samples) * noise_gain if noise is not None else None
        self._start = start
        self._index = 0  # samples produced so far
        self._user: list[tuple[int, Float32Array, Speech]] = []
        self._user_end = 0
        self._remote: list[tuple[int, Float32Array, Speech]] = []
        self._robot: deque[Float32Array] = deque()
        self._robot_queued = 0
        self._drained = asyncio.Event()
        self._drained.set()
        self._tick = asyncio.Event()
        self._closed = False
        self._wall0: float | None = None  # the loop time of stream time `start` (paced rooms, once started)
        self._perf0: float | None = None  # the same moment on `time.perf_counter`, the pipeline's clock
        self.played: list[tuple[float, AudioChunk]] = []  # the robot's speech as it sounded
        self._record = record
        self._recorded: list[AudioChunk] = []
        self.mic = RoomMicrophone(self)
        self.speaker = RoomSpeaker(self)

    # --- time -----------------------------------------------------------------------------

    @property
    def now(self) -> float:
        """Stream time up to which the microphone has produced audio."""
        return self._start + self._index / RATE

    def _wall_index(self) -> int:
        """The stream position (samples) of the present moment: where audio written now sounds.
        An unpaced room (or one not yet started) has no such moment: the next chunk's start."""
        if self._wall0 is None or math.isinf(self.speed):
            return self._index
        due = round((asyncio.get_running_loop().time() - self._wall0) * self.speed * RATE)
        return max(self._index, due)

    def capture_time(self, t: float) -> float | None:
        """The `time.perf_counter` time at which stream time `t` is captured (None while the
        room has not started, or is unpaced): the room's own clock, as a sound card stamps
        its buffers."""
        if self._perf0 is None or math.isinf(self.speed):
            return None
        return self._perf0 + (t - self._start) / self.speed

    def _at(self, t: float | None) -> int:
        return self._index if t is None else max(self._index, round((t - self._start) * RATE))

    async def until(self, t: float, timeout: float = 60.0) -> None:
        """Wait until the microphone has produced audio up to stream time `t`."""
        async with asyncio.timeout(timeout):
            while self.now < t and not self._closed:
                self._tick.clear()
                await self._tick.wait()

    # --- what sounds in the room ------------------------------------------------------------

    def say(self, audio: AudioChunk, *, at: float | None = None, gap_s: float = 0.0) -> Speech:
        """The person speaks `audio`: at stream time `at`, or after what they are saying now
        (plus `gap_s`), never before now (the present moment, even when the microphone's
        consumer has fallen behind it)."""
        samples = as_float32(convert(audio, _F32).samples)
        # "now" is the present moment, as for the robot's speaker (see `_wall_index`)
        i0 = self._at(at) if at is not None else max(self._wall_index(), self._user_end + round(gap_s * RATE))
        speech = Speech(self._start + i0 / RATE, self._start + (i0 + samples.shape[0]) / RATE)
        self._user.append((i0, samples, speech))
        self._user_end = max(self._user_end, i0 + samples.shape[0])
        return speech

    def play_remote(self, audio: AudioChunk, *, at: float | None = None) -> Speech:
        """A video call's remote participant talks through the robot's speaker."""
        samples = as_float32(convert(audio, _F32).samples)
        i0 = self._at(at)
        speech = Speech(self._start + i0 / RATE, self._start + (i0 + samples.shape[0]) / RATE)
        self._remote.append((i0, samples, speech))
        return speech

    @property
    def robot_speaking(self) -> bool:
        return self._robot_queued > 0

    def close(self) -> None:
        """End the microphone stream (the pipeline then finishes)."""
        self._closed = True
        self._tick.set()
        self._drained.set()

    # --- the microphone ------------------------------------------------------------------------

    def _produce(self) -> AudioChunk:
        n = self.chunk_frames
        i0 = self._index
        t0 = self.now
        played = self._take_robot(n)
        remote = self._mix(self._remote, i0, n)
        out = self._mix(self._user, i0, n)
        if played is not None or np.any(remote):
            ref = remote if played is None else remote + played
            self.reference.place(AudioChunk(ref.astype(np.float32), _F32), t0)
            if played is not None:
                self.played.append((t0, AudioChunk(float32_to_int16(played), MODEL_FORMAT, t0)))
        if self._taps:
            history = self.reference.window(t0 - self._echo_len / RATE, self._echo_len + n)
            for delay, gain in self._taps:
                out += gain * history[self._echo_len - delay : self._echo_len - delay + n]
        if self._noise is not None and self._noise.shape[0]:
            idx = (np.arange(i0, i0 + n)) % self._noise.shape[0]
            out += self._noise[idx]
        self._index += n
        for items in (self._user, self._remote):
            for entry in list(items):
                if entry[0] + entry[1].shape[0] <= self._index:
                    entry[2].done.set()
                    items.remove(entry)
        if self._robot_queued == 0:
            self._drained.set()
        chunk = AudioChunk(float32_to_int16(out), MODEL_FORMAT, t0)
        if self._record:
            self._recorded.append(chunk)
        return chunk

    def recording(self) -> AudioChunk | None:
        """Everything the microphone heard (with ``record=True``), joined."""
        return concat(self._recorded) if self._recorded else None

    @staticmethod
    def _mix(items: list[tuple[int, Float32Array, Speech]], i0: int, n: int) -> Float32Array:
        out = np.zeros(n, dtype=np.float32)
        for start, samples, _ in items:
            lo, hi = max(i0, start), min(i0 + n, start + samples.shape[0])
            if hi > lo:
                out[lo - i0 : hi - i0] += samples[lo - start : hi - start]
        return out

    def _take_robot(self, n: int) -> Float32Array | None:
        if not self._robot:
            return None
        out = np.zeros(n, dtype=np.float32)
        filled = 0
        while filled < n and self._robot:
            head = self._robot[0]
            take = min(n - filled, head.shape[0])
            out[filled : filled + take] = head[:take]
            filled += take
            if take == head.shape[0]:
                self._robot.popleft()
            else:
                self._robot[0] = head[take:]
        self._robot_queued -= filled
        return out

    async def _chunks(self) -> AsyncIterator[AudioChunk]:
        loop = asyncio.get_running_loop()
        wall0 = self._wall0 = loop.time()
        self._perf0 = time.perf_counter()
        produced = 0
        while not self._closed:
            due = wall0 + (produced + 1) * self.chunk_frames / RATE / self.speed
            delay = due - loop.time()
            if delay > 0:
                await asyncio.sleep(delay)  # pacing like a sound card, not a test wait
            if self._closed:
                break
            chunk = self._produce()
            produced += 1
            self._tick.set()
            yield chunk
        self._drained.set()


class RoomMicrophone:
    """The room's microphone as an `AudioSource` (16 kHz mono int16); iterate once."""

    def __init__(self, room: SimulatedRoom) -> None:
        self._room = room
        self._iterated = False

    @property
    def format(self) -> AudioFormat:
        return MODEL_FORMAT

    @property
    def speed(self) -> float:
        """Stream seconds per wall second (`voice.clock.StreamAnchor` maps stream time with it)."""
        return self._room.speed

    def capture_time(self, t: float) -> float | None:
        """When stream time `t` was captured, on `time.perf_counter` (`SimulatedRoom.capture_time`)."""
        return self._room.capture_time(t)

    def __aiter__(self) -> AsyncIterator[AudioChunk]:
        if self._iterated:
            raise AudioError("the room microphone can be iterated once")
        self._iterated = True
        return self._room._chunks()

    async def aclose(self) -> None:
        self._room.close()


class RoomSpeaker:
    """The robot's speaker in the room, an `AudioSink`: audio is queued and sounds as the
    microphone's time advances; `stop()` drops what has not sounded yet."""

    def __init__(self, room: SimulatedRoom) -> None:
        self._room = room
        self.stop_count = 0

    async def write(self, chunk: AudioChunk) -> None:
        room = self._room
        samples = as_float32(convert(chunk, _F32).samples)
        if room._closed:
            return
        if room._robot_queued == 0:
            # the speaker was silent: this sounds from the present moment on, never before it
            # was written (the next chunk may have begun up to a chunk earlier)
            lead = room._wall_index() - room._index
            if lead > 0:
                samples = np.concatenate([np.zeros(lead, dtype=np.float32), samples])
        room._robot.append(samples)
        room._robot_queued += samples.shape[0]
        room._drained.clear()

    async def drain(self) -> None:
        await self._room._drained.wait()

    def stop(self) -> None:
        room = self._room
        self.stop_count += 1
        room._robot.clear()
        room._robot_queued = 0
        room._drained.set()

    async def aclose(self) -> None:
        self.stop()
