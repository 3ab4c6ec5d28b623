"""The soak's microphone: the simulated room's, run in accelerated stream time.

The room is made unpaced (`SimulatedRoom(speed=math.inf)`): each chunk is produced when the
pipeline asks for it, so while nothing is going on (background noise, the person talking) the
stream runs as fast as the front end (echo canceller, wake word, VAD) takes it. While the
assistant is busy (a turn, its speech, a drive) the parts that live on the wall clock — the
model, speech synthesis, the sim robot's motion — would otherwise see minutes of stream time
go by per second, so this source then paces the stream at real time. `paced_s` / `free_s`
say how much stream time went each way.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Callable

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat
from robovoice.voice.room import RoomMicrophone


class StreamClock:
    """An `AudioSource` over an unpaced room microphone; `busy()` says when to pace at 1x."""

    def __init__(self, mic: RoomMicrophone, busy: Callable[[], bool] = lambda: False) -> None:
        self._mic = mic
        self.busy = busy
        self.paced_s = 0.0
        self.free_s = 0.0

    @property
    def format(self) -> AudioFormat:
        return MODEL_FORMAT

    def __aiter__(self) -> AsyncIterator[AudioChunk]:
        return self._chunks()

    async def _chunks(self) -> AsyncIterator[AudioChunk]:
        loop = asyncio.get_running_loop()
        anchor: tuple[float, float] | None = None  # (wall, stream) when pacing began
        async for chunk in self._mic:
            if self.busy():
                if anchor is None:
                    anchor = (loop.time(), chunk.timestamp)
                delay = anchor[0] + (chunk.timestamp - anchor[1]) - loop.time()
                if delay > 0:
                    await asyncio.sleep(delay)  # real time while the wall-clock parts work
                self.paced_s += chunk.duration_s
            else:
                anchor = None
                self.free_s += chunk.duration_s
            yield chunk

    async def aclose(self) -> None:
        await self._mic.aclose()
