"""What a heard command becomes before the model sees it: wake phrase removed, trimmed,
encoded as WAV, transcribed (speculatively, inside the end-of-turn silence), and checked
against what the robot itself just said."""

from __future__ import annotations

import asyncio
import difflib
import io
import re
import time
import wave
from collections import deque
from collections.abc import Callable, Coroutine
from dataclasses import dataclass
from typing import Any

from robovoice.assistant.metrics import TurnMetrics
from robovoice.audio.format import AudioChunk, convert
from robovoice.audio.stt import Transcriber, Transcript
from robovoice.voice.inference import ModelExecutor
from robovoice.voice.stop import normalise

WAKE_LOOKBACK_S = 1.6  # a command's audio starts at most this long before its wake word
# ... and this long when an unsure transcript is tried again without the talk before the
# phrase: the detector fires ~0.76 s after a "Hey Jarvis" begins (24 made-up commands after
# television talk, soak voices); the longer first cut keeps a slow speaker's "hey"
WAKE_PHRASE_S = 1.0


def wav_bytes(audio: AudioChunk) -> bytes:
    """A chunk as a complete 16-bit PCM WAV file (what `AudioPart` sends); float samples are
    converted to 16-bit first."""
    if audio.format.width != 2:
        audio = convert(audio, audio.format.with_(width=2))
    buf = io.BytesIO()
    with wave.open(buf, "wb") as wf:
        wf.setnchannels(audio.format.channels)
        wf.setsampwidth(2)
        wf.setframerate(audio.format.rate)
        wf.writeframes(audio.bytes)
    return buf.getvalue()


WAKE_PREFIX_WORDS = 4  # words of other talk a transcript may hold before the whole wake phrase


def _wake_phrase_end(text: str, phrase: str) -> int | None:
    """Where the wake phrase ends in `text` (a character index), or None. The phrase is
    matched loosely, as speech-to-text spells it ("Hey, Jarvis,", "Hey Jervis", "Jarvis,"):
    its last words at the very start, or the whole phrase after a few words of other talk
    heard in the same breath ("Breathe, hey Jarvis, …": a television's last word before the
    person spoke)."""
    words = list(re.finditer(r"[A-Za-z']+", text))
    target = phrase.lower().split()

    for k in range(len(target), 0, -1):
        if len(words) >= k and _like(" ".join(w.group(0) for w in words[:k]), " ".join(target[-k:])):
            return words[k - 1].end()
    k = len(target)  # after other talk: the whole phrase, each word close ("the Jarvis mode" is no wake)
    for start in range(1, min(WAKE_PREFIX_WORDS, len(words) - k) + 1):
        if all(_like(words[start + i].group(0), target[i]) for i in range(k)):
            return words[start + k - 1].end()
    return None


def _like(heard: str, said: str) -> bool:
    """`heard` is `said` as speech-to-text may spell it."""
    return difflib.SequenceMatcher(None, heard.lower(), said).ratio() >= 0.75


_GREETINGS = frozenset({"hey", "hi", "hello", "hiya", "oi", "okay", "ok"})
_NOT_NAMES = frozenset({"i", "i'm", "i'd", "i'll", "i've", "robot"})


def addressed_elsewhere(text: str, phrase: str = "hey jarvis") -> bool:
    """A transcript that opens by calling someone else by name ("Hey Charlie, go along to the
    front door"): the wake word fired on a near miss of its phrase, and the words show it.
    Whisper capitalises a name it hears; a mishearing of the wake name itself ("Hey Travis")
    is close to it and still counts as the phrase."""
    if _wake_phrase_end(text, phrase) is not None:
        return False
    words = re.findall(r"[A-Za-z']+", text)
    name = phrase.split()[-1].lower()
    return (len(words) >= 2 and words[0].lower() in _GREETINGS and words[1][:1].isupper()
            and words[1].lower() not in _NOT_NAMES
            and difflib.SequenceMatcher(None, words[1].lower(), name).ratio() < 0.6)


def names_robot(text: str, phrase: str = "hey jarvis") -> bool:
    """Whether a transcript opens with the wake phrase's name spelt exactly ("Hey Jarvis,",
    "Jarvis,", after at most `WAKE_PREFIX_WORDS` other words): what an unsure wake word must
    show before it counts. Stricter than `strip_wake_words`: "Hey Travis, go to the kitchen"
    (a wake score of 0.48) is somebody else's name."""
    name = re.findall(r"[a-z']+", phrase.lower())[-1:]
    words = [w.lower() for w in re.findall(r"[A-Za-z']+", text)]
    return bool(name) and name[0] in words[:len(phrase.split()) + WAKE_PREFIX_WORDS]


def strip_wake_words(text: str, phrase: str = "hey jarvis") -> str:
    """Remove the wake phrase (and anything heard before it) from a transcript; the text
    after it is kept as said."""
    end = _wake_phrase_end(text, phrase)
    return text.strip() if end is None else text[end:].lstrip(" ,.!?;:-").strip()


def trim_to_wake(audio: AudioChunk, wake_at: float | None, lookback_s: float = WAKE_LOOKBACK_S) -> AudioChunk:
    """Drop what was said long before the wake word (chatter in the same utterance)."""
    if wake_at is None:
        return audio
    cut = round((wake_at - lookback_s - audio.timestamp) * audio.format.rate)
    if cut <= 0:
        return audio
    return AudioChunk(audio.samples[cut:], audio.format, audio.timestamp + cut / audio.format.rate)


Transcription = asyncio.Task[tuple[Transcript, float]]
TaskFactory = Callable[[Coroutine[Any, Any, tuple[Transcript, float]]], Transcription]


@dataclass(frozen=True, slots=True)
class _Speculation:
    onset: float
    at: float
    task: Transcription
    hint: str


class Transcribing:
    """Speech-to-text on the model's executor, with one speculative run at a time: started
    at a pause of an utterance (`speculate`), used when the utterance turns out to have
    ended there (`take`), dropped when speech went on."""

    def __init__(self, stt: Transcriber, executor: ModelExecutor) -> None:
        self.stt = stt
        self._executor = executor
        self._speculation: _Speculation | None = None
        self.speculated = 0  # speculative runs started
        self.reused = 0  # ... whose transcript was used for the utterance

    async def transcribe(self, audio: AudioChunk, hint: str = "", *, urgent: bool = False) -> tuple[Transcript, float]:
        """(the transcript, scores included, and the milliseconds it took, waiting for the
        model's thread included). `hint`: see `Transcriber.transcribe`. `urgent`: before the
        transcriptions still waiting (a stop check)."""
        started = time.perf_counter()
        run = self._executor.run_first if urgent else self._executor.run
        transcript = await run(self.stt.transcribe, audio, hint)
        return transcript, (time.perf_counter() - started) * 1000.0

    async def transcript_for(
        self, audio: AudioChunk, metrics: TurnMetrics, speculation: Transcription | None, hint: str,
        *, urgent: bool = False,
    ) -> Transcript:
        """The transcript of `audio`: the speculative run's when it covers the utterance,
        else a run now; its time and the ``transcript`` mark go into `metrics`."""
        transcript, took_ms = await speculation if speculation is not None else \
            await self.transcribe(audio, hint, urgent=urgent)
        metrics.stt_ms += took_ms
        metrics.mark("transcript", max(metrics.start, time.perf_counter()))
        return transcript

    async def text_for(
        self, audio: AudioChunk, metrics: TurnMetrics, speculation: Transcription | None, hint: str
    ) -> str:
        """`transcript_for`'s text, before the transcriptions still waiting (a stop check,
        which needs no scores)."""
        return (await self.transcript_for(audio, metrics, speculation, hint, urgent=True)).text

    def speculate(
        self, onset: float, at: float, audio: AudioChunk, create_task: TaskFactory, hint: str = ""
    ) -> Transcription:
        """Start transcribing the utterance so far (the one before is dropped); its task."""
        self.drop()
        self.speculated += 1
        task = create_task(self.transcribe(audio, hint))
        self._speculation = _Speculation(onset, at, task, hint)
        return task

    def drop(self) -> None:
        if self._speculation is not None:
            self._speculation.task.cancel()
            self._speculation = None

    def take(self, start: float, end: float, hint: str = "") -> Transcription | None:
        """The speculative run covering the utterance `start`..`end` with this `hint`, if
        there is one."""
        spec, self._speculation = self._speculation, None
        if spec is None:
            return None
        if abs(spec.onset - start) < 1e-6 and spec.at >= end - 1e-6 and spec.hint == hint:
            self.reused += 1
            return spec.task
        spec.task.cancel()
        return None


class OwnWords:
    """What the robot said lately, to recognise its own words coming back through the
    microphone in a transcript (a stop the robot said itself is no stop)."""

    def __init__(self, keep_s: float = 15.0, clock: Callable[[], float] = time.monotonic) -> None:
        self._said: deque[tuple[float, str]] = deque()
        self._keep_s = keep_s
        self._clock = clock

    def add(self, text: str) -> None:
        now = self._clock()
        self._said.append((now, normalise(text)))
        while self._said and now - self._said[0][0] > self._keep_s:
            self._said.popleft()

    def contains(self, heard: str) -> bool:
        """Whether the robot recently said the words of `heard` (in this order)."""
        words = normalise(heard)
        if not words:
            return False
        now = self._clock()
        return any(now - t <= self._keep_s and f" {words} " in f" {said} " for t, said in self._said)

    def resembles(self, heard: str, ratio: float = 0.6) -> bool:
        """Whether `heard` reads like the start of something the robot said lately, misheard:
        "Alright, hold on." for its "All right, I won't." (audio test v52). Letters compared
        without spaces, over as much of what it said as was heard."""
        letters = normalise(heard).replace(" ", "")
        if not letters:
            return False
        now = self._clock()
        return any(now - t <= self._keep_s and _likeness(letters, said.replace(" ", "")[:len(letters) + 4]) >= ratio
                   for t, said in self._said)


def _likeness(heard: str, said: str) -> float:
    return difflib.SequenceMatcher(None, heard, said).ratio()
