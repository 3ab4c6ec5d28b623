"""Spoken output: sentences in, audio out, sentence N playing while N+1 is synthesised.

Two stages joined by a small queue, each a task of `SpeechOutput.run()`:

    say(text) -> [text queue] -> synthesise (TTS executor) -> [audio queue] -> sink.write

`interrupt()` is the barge-in control: it drops everything queued in both stages, stops the
sink (its queued audio is dropped at once) and discards a synthesis already running. It
returns immediately. `withdraw(handle)` takes back one sentence that has not started playing
(an acknowledgement whose tool failed at once). Each piece of speech carries the turn it belongs to and that turn's
`TurnMetrics`, which get ``first_audio`` when the turn's first audio goes to the speaker.
"""

from __future__ import annotations

import asyncio
import itertools
import logging
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass

from robovoice.assistant.events import notify
from robovoice.assistant.metrics import TurnMetrics
from robovoice.assistant.speech_guard import unspeakable_in, without_end_marker
from robovoice.audio.format import AudioChunk, AudioFormat, concat, convert
from robovoice.audio.streams import AudioSink
from robovoice.audio.tts import Synthesizer
from robovoice.voice.events import SentenceSpoken
from robovoice.voice.inference import ModelExecutor

log = logging.getLogger(__name__)

SpokenObserver = Callable[[SentenceSpoken], Awaitable[None] | None]


@dataclass(frozen=True, slots=True)
class _Say:
    text: str
    turn: int | None
    kind: str
    metrics: TurnMetrics | None
    epoch: int
    handle: int


@dataclass(frozen=True, slots=True)
class _Audio:
    say: _Say
    chunk: AudioChunk | None  # None: nothing to play (withdrawn, or silent)


class SpeechOutput:
    """See the module docstring. `sink_format`: convert audio for a sink that needs a fixed
    format (a sound card); None hands the synthesiser's audio over as it is."""

    def __init__(
        self,
        tts: Synthesizer,
        sink: AudioSink,
        executor: ModelExecutor,
        *,
        sink_format: AudioFormat | None = None,
        on_spoken: SpokenObserver | None = None,
        queue_size: int,
    ) -> None:
        self.tts = tts
        self.sink = sink
        self._executor = executor
        self._sink_format = sink_format
        self._on_spoken = on_spoken
        self._texts: asyncio.Queue[_Say] = asyncio.Queue()
        self._audio: asyncio.Queue[_Audio] = asyncio.Queue(maxsize=max(1, queue_size // 4))
        self._epoch = 0
        self._pending = 0  # said but not yet handed to the sink (or dropped)
        self._unplayed = False  # handed to the sink, drain not yet confirmed
        self._idle = asyncio.Event()
        self._idle.set()
        self._handles = itertools.count(1)
        self._unstarted: set[int] = set()  # handles said whose playback has not started
        self._withdrawn: set[int] = set()
        self.recordings: dict[int | None, list[AudioChunk]] = {}
        self.interrupts = 0

    # --- control ----------------------------------------------------------------------

    @property
    def busy(self) -> bool:
        """Something is queued, being synthesised, or still playing."""
        return not self._idle.is_set()

    def say(
        self, text: str, *, turn: int | None = None, kind: str = "reply", metrics: TurnMetrics | None = None
    ) -> int | None:
        """Queue `text`; its handle (for `withdraw`), None when there is nothing to say (or it
        carries tool-call syntax or the model's instructions, never spoken: `speech_guard`)."""
        text = without_end_marker(text).strip()
        if not text:
            return None
        if (unspeakable := unspeakable_in(text)) is not None:
            log.warning("not speaking a sentence with tool-call syntax or the model's instructions %r: %r",
                        unspeakable, text[:200])
            return None
        handle = next(self._handles)
        self._pending += 1
        self._unstarted.add(handle)
        self._idle.clear()
        self._texts.put_nowait(_Say(text, turn, kind, metrics, self._epoch, handle))
        return handle

    def withdraw(self, handle: int | None) -> bool:
        """Take back what `say` queued under `handle` unless it started playing; whether it did."""
        if handle is None or handle not in self._unstarted:
            return False
        self._unstarted.discard(handle)
        self._withdrawn.add(handle)
        log.info("speech %d withdrawn before it was played", handle)
        return True

    def interrupt(self) -> None:
        """Barge-in: drop all queued and playing speech now."""
        self._epoch += 1
        self.interrupts += 1
        dropped = 0
        for queue in (self._texts, self._audio):
            while not queue.empty():
                queue.get_nowait()
                dropped += 1
        self._pending = 0
        self._unstarted.clear()
        self._withdrawn.clear()
        self.sink.stop()
        self._unplayed = False
        self._idle.set()
        log.info("speech interrupted (%d queued item(s) dropped)", dropped)

    async def idle(self, timeout: float | None = None) -> bool:
        """Wait until everything said has been played (or dropped); False on timeout."""
        try:
            async with asyncio.timeout(timeout):
                await self._idle.wait()
        except TimeoutError:
            return False
        return True

    def take_recording(self, turn: int | None) -> AudioChunk | None:
        """The audio spoken for `turn` so far, joined (and forgotten)."""
        chunks = self.recordings.pop(turn, [])
        if not chunks:
            return None
        fmt = chunks[0].format
        return concat([c if c.format == fmt else convert(c, fmt) for c in chunks])

    # --- the two stages -----------------------------------------------------------------

    async def run(self) -> None:
        """Run both stages until cancelled."""
        async with asyncio.TaskGroup() as group:
            group.create_task(self._synthesise(), name="speech-synthesis")
            group.create_task(self._play(), name="speech-playback")

    async def _synthesise(self) -> None:
        while True:
            item = await self._texts.get()
            if item.epoch != self._epoch:
                continue
            if item.handle in self._withdrawn:
                await self._audio.put(_Audio(item, None))
                continue
            started = time.perf_counter()
            chunk = await self._executor.run(self.tts.synthesize, item.text)
            if item.metrics is not None:
                item.metrics.tts_ms += (time.perf_counter() - started) * 1000.0
            if item.epoch != self._epoch:  # interrupted while synthesising
                continue
            if self._sink_format is not None and chunk.format != self._sink_format:
                chunk = convert(chunk, self._sink_format)
            await self._audio.put(_Audio(item, chunk if chunk.num_frames else None))

    async def _play(self) -> None:
        while True:
            audio = await self._audio.get()
            item = audio.say
            if item.epoch != self._epoch:
                continue
            self._unstarted.discard(item.handle)
            if audio.chunk is not None and item.handle not in self._withdrawn:
                if item.metrics is not None:
                    item.metrics.mark("first_audio")
                self._unplayed = True
                await self.sink.write(audio.chunk)
                self.recordings.setdefault(item.turn, []).append(audio.chunk)
                await notify(self._on_spoken,
                             SentenceSpoken(item.turn, item.text, item.kind, audio.chunk.duration_s))
                if item.epoch != self._epoch:
                    continue
            self._withdrawn.discard(item.handle)
            self._pending = max(0, self._pending - 1)
            if self._pending == 0 and self._audio.empty():
                epoch = self._epoch
                if self._unplayed:
                    await self.sink.drain()  # returns at once when interrupt() stops the sink
                if epoch == self._epoch:
                    self._unplayed = False
                    self._maybe_idle()

    def _maybe_idle(self) -> None:
        if self._pending == 0 and not self._unplayed and self._audio.empty():
            self._idle.set()

