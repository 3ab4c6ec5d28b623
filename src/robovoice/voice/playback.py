"""Playback on a real speaker that also feeds the echo canceller's reference.

`ReferencedSink` wraps a device sink (`audio.devices.SpeakerSink`): every chunk written is
placed in the `PlaybackReference` at the time it will sound, on the microphone's clock
(the event loop's clock, which `MicrophoneSource` stamps its chunks with), estimated as
"after what is queued, and not before now + the output latency"; `stop()` (barge-in)
truncates the reference at once. The echo canceller's filter (128 ms) absorbs the error
of that estimate.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable

from robovoice.audio.format import AudioChunk
from robovoice.audio.streams import AudioSink
from robovoice.voice.echo import PlaybackReference


class ReferencedSink:
    """An `AudioSink` that records what it plays into a `PlaybackReference`."""

    def __init__(
        self,
        sink: AudioSink,
        reference: PlaybackReference,
        *,
        output_latency_s: float = 0.05,
        clock: Callable[[], float] | None = None,
    ) -> None:
        self.sink = sink
        self.reference = reference
        self._latency = output_latency_s
        self._clock = clock
        self._end = 0.0

    def _now(self) -> float:
        return self._clock() if self._clock is not None else asyncio.get_running_loop().time()

    async def write(self, chunk: AudioChunk) -> None:
        start = max(self._now() + self._latency, self._end)
        self._end = self.reference.place(chunk, start)
        await self.sink.write(chunk)

    async def drain(self) -> None:
        await self.sink.drain()

    def stop(self) -> None:
        now = self._now()
        self.reference.truncate(now)
        self._end = now
        self.sink.stop()

    async def aclose(self) -> None:
        await self.sink.aclose()
