"""A microphone that may fail, stall, or disappear and return (issue 14's audio-device faults).

    guard = GuardedSource(lambda: MicrophoneSource(MODEL_FORMAT), stall_s=2.0, give_up_s=60.0)
    pipeline = VoicePipeline(..., source=guard, ...)
    guard.on_event = DeviceReaction(pipeline)      # stop the robot, say what happened
    await pipeline.run()
    if guard.failure: print(guard.failure)         # the device never came back

`GuardedSource` opens the source with its factory and re-yields its chunks (16 kHz mono,
one continuous stream clock). When the source raises, or sends nothing for `stall_s`
(a USB microphone unplugged mid-stream stops calling back; nothing raises), the device is
*lost*: it is closed, `on_event(DeviceLost)` is told, and the factory is tried again every
`retry_s`. When chunks flow again, the time it was gone is given to the pipeline as
silence (an utterance cut off by the fault ends there; stream time stays wall time) and
`on_event(DeviceBack)` is told. After `give_up_s` without a device the stream ends,
`failure` says why and `on_event(DeviceGone)` is told. A source that *ends* (a WAV file)
just ends the stream.

`DeviceReaction` is what the assistant does about it: when the device is lost, the turn under
way is cancelled and the robot stopped through its stop tool (without a microphone nobody
can say "stop"), and a short explanation is spoken; on return, "I can hear you again".
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import AsyncGenerator, AsyncIterator, Awaitable, Callable
from dataclasses import dataclass

import numpy as np

from robovoice.assistant.events import notify
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat
from robovoice.audio.streams import AudioSource, converted
from robovoice.voice.pipeline import VoicePipeline

log = logging.getLogger(__name__)

_GAP_CHUNK_S = 0.08  # silence for the time the device was gone, in microphone-sized chunks


@dataclass(frozen=True, slots=True)
class DeviceLost:
    reason: str
    at: float  # stream time


@dataclass(frozen=True, slots=True)
class DeviceBack:
    at: float
    gone_s: float


@dataclass(frozen=True, slots=True)
class DeviceGone:
    reason: str
    at: float


DeviceEvent = DeviceLost | DeviceBack | DeviceGone


class GuardedSource:
    """See the module docstring. `on_event`: called (awaited if a coroutine) for each
    `DeviceEvent`; `events`: all of them, in order."""

    def __init__(self, open_source: Callable[[], AudioSource], *, stall_s: float = 2.0, retry_s: float = 0.5,
                 give_up_s: float = 60.0, fmt: AudioFormat = MODEL_FORMAT) -> None:
        if stall_s <= 0 or retry_s <= 0 or give_up_s < 0:
            raise ValueError(f"GuardedSource: stall_s ({stall_s}) and retry_s ({retry_s}) must be > 0, "
                             f"give_up_s ({give_up_s}) >= 0")
        self._open = open_source
        self._fmt = fmt
        self.stall_s, self.retry_s, self.give_up_s = stall_s, retry_s, give_up_s
        self.on_event: Callable[[DeviceEvent], Awaitable[None] | None] | None = None
        self.events: list[DeviceEvent] = []
        self.failure: str | None = None
        self._closed = asyncio.Event()
        self._now = 0.0  # stream time: end of the last chunk given out

    @property
    def format(self) -> AudioFormat:
        return self._fmt

    def __aiter__(self) -> AsyncIterator[AudioChunk]:
        return self._chunks()

    async def aclose(self) -> None:
        self._closed.set()

    async def _tell(self, event: DeviceEvent) -> None:
        self.events.append(event)
        log.warning("audio device: %s", event)
        await notify(self.on_event, event)

    async def _chunks(self) -> AsyncIterator[AudioChunk]:
        loop = asyncio.get_running_loop()
        lost_since: float | None = None  # loop time the device was lost
        started = False
        while not self._closed.is_set():
            reason, ended = "", False
            try:
                source = self._open()
            except Exception as exc:  # the device is not there (yet)
                reason = f"cannot open the audio device: {exc}"
            else:
                stream = converted(aiter(source), self._fmt)
                try:
                    while not self._closed.is_set():
                        chunk = await asyncio.wait_for(anext(stream), self.stall_s)
                        if not started:
                            self._now, started = chunk.timestamp, True
                        if lost_since is not None:
                            gone = loop.time() - lost_since
                            for gap in _silence(self._fmt, gone, self._now):
                                self._now = gap.end_timestamp
                                yield gap
                            lost_since = None
                            await self._tell(DeviceBack(self._now, round(gone, 2)))
                        chunk = AudioChunk(chunk.samples, chunk.format, self._now)  # one clock across devices
                        self._now = chunk.end_timestamp
                        yield chunk
                except StopAsyncIteration:
                    ended = True
                except TimeoutError:
                    reason = f"no audio from the device for {self.stall_s:g} s"
                except Exception as exc:  # a device error mid-stream
                    reason = f"the audio device failed: {exc}"
                finally:
                    if isinstance(stream, AsyncGenerator):
                        with contextlib.suppress(Exception):
                            await stream.aclose()
                    with contextlib.suppress(Exception):
                        await source.aclose()
            if ended or self._closed.is_set():
                return
            if lost_since is None:
                lost_since = loop.time()
                await self._tell(DeviceLost(reason, self._now))
            elif loop.time() - lost_since >= self.give_up_s:
                self.failure = (f"the microphone has been gone for {loop.time() - lost_since:.0f} s ({reason}); "
                                f"check that it is plugged in and not used by another program, then start again")
                await self._tell(DeviceGone(reason, self._now))
                return
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(self._closed.wait(), self.retry_s)


def _silence(fmt: AudioFormat, seconds: float, start: float) -> list[AudioChunk]:
    n = round(_GAP_CHUNK_S * fmt.rate)
    count = max(1, round(seconds / _GAP_CHUNK_S))
    zeros = np.zeros((n, fmt.channels) if fmt.channels > 1 else n, dtype=fmt.dtype)
    return [AudioChunk(zeros, fmt, start + i * n / fmt.rate) for i in range(count)]


LOST_MESSAGE = "I can't hear you any more: my microphone stopped working. I stopped the robot to be safe."
BACK_MESSAGE = "I can hear you again."
GONE_MESSAGE = "My microphone is still gone, so I'm stopping now."


class DeviceReaction:
    """`GuardedSource.on_event` for a running `VoicePipeline`: see the module docstring."""

    def __init__(self, pipeline: VoicePipeline, stop_timeout_s: float = 5.0) -> None:
        self.pipeline = pipeline
        self.stop_timeout_s = stop_timeout_s
        self.stopped: list[bool] = []  # per loss: whether the stop tool answered without error

    async def __call__(self, event: DeviceEvent) -> None:
        p = self.pipeline
        if isinstance(event, DeviceLost):
            p.floor.cancel_active()
            p.speech.interrupt()
            self.stopped.append(await self._stop_robot())
            p.speech.say(LOST_MESSAGE, kind="notice")
        elif isinstance(event, DeviceBack):
            p.speech.say(BACK_MESSAGE, kind="notice")
        else:
            p.speech.say(GONE_MESSAGE, kind="notice")

    async def _stop_robot(self) -> bool:
        tool = self.pipeline.roles.stop
        if tool is None:
            log.warning("the microphone is gone and the robot declares no stop tool: it was not stopped")
            return False
        try:
            async with asyncio.timeout(self.stop_timeout_s):
                outcome = await self.pipeline.tools.call(tool, {})
        except Exception as exc:  # a dead robot link: say so, keep going
            log.error("stopping the robot after the microphone was lost failed: %s", exc)
            return False
        return not outcome.is_error
