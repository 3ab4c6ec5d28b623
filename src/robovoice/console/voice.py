"""Talking to the robot through the page: the browser's microphone and speaker as the voice
pipeline's `AudioSource` and `AudioSink`, and the pipeline `robovoice assist` uses between them.

The page streams 16 kHz mono int16 PCM (little-endian) over the audio WebSocket; `BrowserMic`
yields it as chunks. `BrowserSpeaker` sends the robot's speech back as binary messages (a
4-byte little-endian sample rate, then mono int16 PCM) and keeps real-time pacing, so the
pipeline knows when the robot is still talking (barge-in, echo). One page holds the
microphone at a time; a newer one takes it over.

Push-to-talk: pressing the button counts as the wake word at that moment of the stream
(`VoicePipeline.turns.wake`); hands-free listens for the wake word itself.

The voice models are loaded in the background when the console starts: the page is usable
(typed turns, tools) before they are ready; `status()` says how far it is.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import struct
import tempfile
import time
from collections.abc import AsyncIterator, Callable, Coroutine
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robovoice.assistant.robot_tools import RobotTools
    from robovoice.audio.format import AudioChunk, AudioFormat
    from robovoice.console.hub import EventHub
    from robovoice.console.service import ConsoleAudit
    from robovoice.llm.base import LLMBackend
    from robovoice.voice.models import VoiceModels
    from robovoice.voice.pipeline import VoicePipeline

log = logging.getLogger(__name__)

MIC_RATE = 16000
MAX_QUEUED_CHUNKS = 400  # ~8-25 s of audio: a stalled pipeline drops the oldest, never blocks the socket
SILENCE_ON_RELEASE_S = 1.0  # pushed after a page lets go of the microphone, to end an utterance cleanly

Send = Callable[[bytes], Coroutine[Any, Any, None]]


class BrowserMic:
    """`AudioSource` fed by `push` (raw 16 kHz mono int16 PCM from the page)."""

    def __init__(self) -> None:
        from robovoice.audio.format import MODEL_FORMAT

        self._format = MODEL_FORMAT
        self._queue: asyncio.Queue[bytes | None] = asyncio.Queue(MAX_QUEUED_CHUNKS)
        self._frames = 0
        self.dropped = 0

    @property
    def format(self) -> AudioFormat:
        return self._format

    @property
    def stream_time(self) -> float:
        """Seconds of audio received so far (the pipeline's stream clock)."""
        return self._frames / MIC_RATE

    def push(self, pcm: bytes) -> None:
        if len(pcm) % 2:
            pcm = pcm[:-1]
        if not pcm:
            return
        if self._queue.full():
            self._queue.get_nowait()
            self.dropped += 1
        self._queue.put_nowait(pcm)

    def push_silence(self, seconds: float) -> None:
        self.push(bytes(int(seconds * MIC_RATE) * 2))

    async def __aiter__(self) -> AsyncIterator[AudioChunk]:
        from robovoice.audio.format import AudioChunk

        while True:
            data = await self._queue.get()
            if data is None:
                return
            chunk = AudioChunk.from_bytes(data, self._format, timestamp=self.stream_time)
            self._frames += chunk.num_frames
            yield chunk

    async def aclose(self) -> None:
        while self._queue.full():
            self._queue.get_nowait()
        self._queue.put_nowait(None)


class BrowserSpeaker:
    """`AudioSink` that plays in the page holding the microphone (`send`), paced in real time."""

    def __init__(self) -> None:
        self.send: Send | None = None
        self._until = 0.0  # monotonic time the queued audio ends playing
        self._stopped = asyncio.Event()
        self.sent_s = 0.0

    async def write(self, chunk: AudioChunk) -> None:
        from robovoice.audio.format import convert

        mono = convert(chunk, chunk.format.with_(channels=1, width=2))
        now = time.monotonic()
        self._until = max(self._until, now) + mono.duration_s
        self._stopped.clear()
        self.sent_s += mono.duration_s
        if self.send is not None:
            try:
                await self.send(struct.pack("<I", mono.format.rate) + mono.bytes)
            except Exception as exc:  # the page went away: the audio is lost, the turn goes on
                log.info("the page's speaker is gone (%s)", exc)
                self.send = None

    async def drain(self) -> None:
        remaining = self._until - time.monotonic()
        if remaining <= 0:
            return
        with contextlib.suppress(TimeoutError):
            async with asyncio.timeout(remaining):
                await self._stopped.wait()

    def stop(self) -> None:
        self._until = time.monotonic()
        self._stopped.set()
        send = self.send
        if send is not None:  # tell the page to drop what it has queued: a zero-rate header
            task: asyncio.Task[None] = asyncio.get_running_loop().create_task(send(struct.pack("<I", 0)))
            task.add_done_callback(lambda t: t.exception() if not t.cancelled() else None)

    async def aclose(self) -> None:
        self.stop()


class VoiceBridge:
    """The voice pipeline between the page's microphone and speaker (see module docstring).

    `load_models`: a blocking function returning the `VoiceModels` (run in a thread)."""

    def __init__(self, load_models: Callable[[], VoiceModels], backend: LLMBackend, tools: RobotTools,
                 *, pipeline_options: dict[str, Any] | None = None, answers_dir: Path | None = None) -> None:
        self._load_models = load_models
        self._backend = backend
        self._tools = tools
        self._options = dict(pipeline_options or {})
        self._tmp: tempfile.TemporaryDirectory[str] | None = None
        if answers_dir is None:
            self._tmp = tempfile.TemporaryDirectory(prefix="robovoice-console-")
            answers_dir = Path(self._tmp.name)
        self.answers_dir = answers_dir
        self.mic = BrowserMic()
        self.speaker = BrowserSpeaker()
        self.pipeline: VoicePipeline | None = None
        self._state = "loading"
        self._detail = ""
        self._holder: object | None = None
        self._hub: EventHub | None = None
        self._audit: ConsoleAudit | None = None

    def attach(self, hub: EventHub, audit: ConsoleAudit) -> None:
        self._hub, self._audit = hub, audit

    def status(self) -> dict[str, Any]:
        return {"state": self._state, "detail": self._detail, "connected": self._holder is not None,
                "heard_s": round(self.mic.stream_time, 1), "spoken_s": round(self.speaker.sent_s, 1)}

    def answer_path(self, turn: int, *, typed: bool = False) -> Path:
        return self.answers_dir / (f"typed-{turn:02d}.wav" if typed else f"turn-{turn:02d}.wav")

    async def typed_answer(self, turn: int, timeout_s: float = 120.0) -> str | None:
        """Once a typed turn's answer has been spoken (`Console.say` has the pipeline say it),
        keep it as that turn's WAV; its URL (None: nothing was spoken)."""
        from robovoice.audio.wav import write_wav

        if self.pipeline is None:
            return None
        await self.pipeline.speech.idle(timeout=timeout_s)
        audio = self.pipeline.speech.take_recording(None)  # typed answers are spoken outside any voice turn
        if audio is None:
            return None
        await asyncio.to_thread(write_wav, self.answer_path(turn, typed=True), audio)
        return f"/api/answers/typed-{turn}.wav"

    async def _observe(self, event: object) -> None:
        if self._hub is None:
            return
        turn = getattr(event, "turn", None)
        if type(event).__name__ == "SentenceSpoken" and turn is None and not self._hub.voice_turn_open:
            return  # a typed turn's answer, spoken: that turn shows it already
        url = (f"/api/answers/{turn}.wav" if type(event).__name__ == "VoiceTurnFinished" and isinstance(turn, int)
               else None)
        self._hub.voice_event(event, answer_url=url)
        if self._audit is not None:
            self._audit.observe(event, "voice")

    async def run(self) -> None:
        from robovoice.voice.pipeline import VoicePipeline

        try:
            models = await asyncio.to_thread(self._load_models)
            self.pipeline = VoicePipeline(models, self._backend, self._tools, source=self.mic, sink=self.speaker,
                                          observer=self._observe, output_dir=self.answers_dir, **self._options)
        except Exception as exc:  # no voice models installed: the console still serves typed turns
            self._state, self._detail = "failed", f"{type(exc).__name__}: {exc}"
            log.warning("the console's voice is off: %s", self._detail)
            return
        self._state = "ready"
        log.info("the console's voice is ready")
        try:
            await self.pipeline.run(finish_timeout_s=5.0)
        finally:
            self._state = "stopped"
            if self._tmp is not None:
                self._tmp.cleanup()

    # --- the page holding the microphone ---------------------------------------------------

    def connect(self, holder: object, send: Send) -> None:
        """`holder` (a WebSocket) now owns the microphone and hears the robot."""
        self._holder = holder
        self.speaker.send = send

    def disconnect(self, holder: object) -> None:
        if self._holder is holder:
            self._holder = None
            self.speaker.send = None
            self.mic.push_silence(SILENCE_ON_RELEASE_S)

    def holds(self, holder: object) -> bool:
        return self._holder is holder

    def push_to_talk(self) -> None:
        """The talk button was pressed: treat this moment of the stream as the wake word."""
        if self.pipeline is not None:
            self.pipeline.turns.wake(self.mic.stream_time)
