"""Self-voice rejection below the pipeline (the playback reference, the echo canceller, the
echo meter) and the speech output (synthesis of sentence N+1 while N plays, barge-in)."""

from __future__ import annotations

import asyncio
import math
import threading
import time

import numpy as np
import pytest

from robovoice.audio.fakes import ToneSynthesizer
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, as_float32
from robovoice.audio.wav import MemorySink
from robovoice.voice.echo import EchoCanceller, PlaybackReference
from robovoice.voice.inference import ModelExecutor
from robovoice.voice.listener import EchoMeter
from robovoice.voice.room import EchoPath
from robovoice.voice.speech import SpeechOutput

from .voice_kit import ROOM_ECHO, clip

F32 = MODEL_FORMAT.with_(width=4)


def _db(x: np.ndarray) -> float:
    return 10 * math.log10(float(np.mean(x.astype(np.float64) ** 2)) + 1e-20)


def _echo(x: np.ndarray, path: EchoPath = ROOM_ECHO) -> np.ndarray:
    h = np.zeros(path.length)
    for delay, gain in path.taps():
        h[delay] += gain
    return np.convolve(x, h)[: len(x)].astype(np.float32)


def test_playback_reference_places_truncates_and_reads_windows() -> None:
    ref = PlaybackReference(keep_s=2.0)
    ones = AudioChunk(np.ones(1600, dtype=np.float32) * 0.5, F32)
    end = ref.place(ones, 10.0)
    assert end == pytest.approx(10.1) and ref.end_time == pytest.approx(10.1)
    w = ref.window(9.95, 3200)
    assert not w[:800].any() and np.allclose(w[800:2400], 0.5) and not w[2400:].any()
    assert ref.playing(10.05, 10.06) and not ref.playing(10.2, 10.3)
    ref.truncate(10.05)
    assert np.allclose(ref.window(10.0, 800), 0.5) and not ref.window(10.05, 800).any()
    ref.place(ones, 100.0)  # far later: old audio is forgotten, memory stays bounded
    assert not ref.window(10.0, 800).any() and ref.window(100.0, 10)[0] == pytest.approx(0.5)


def test_echo_canceller_converges_on_speech_and_keeps_the_person_in_double_talk() -> None:
    robot = as_float32(clip("audio/tv_espeak_weather").samples)
    person = as_float32(clip("audio/wakeonly_piper").samples)
    x = np.concatenate([robot, robot])
    n = len(x) - len(x) % 1280
    x = x[:n]
    echo = _echo(x)
    near = np.zeros(n, dtype=np.float32)
    at = len(robot)
    near[at : at + len(person)] = person[: n - at]
    mic = echo + near
    aec = EchoCanceller()
    out = np.concatenate([aec.process(mic[i : i + 1280], x[i : i + 1280])[0] for i in range(0, n, 1280)])
    left = out - near  # what is left of the echo
    converged = slice(3 * 16000, at)
    assert _db(echo[converged]) - _db(left[converged]) > 15.0
    talk = slice(at, at + len(person))
    assert _db(echo[talk]) - _db(left[talk]) > 15.0, "double talk does not undo the cancellation"
    assert _db(out[talk] - near[talk]) < _db(near[talk]) - 15.0, "the person comes through"


def test_echo_canceller_passes_audio_through_while_nothing_plays() -> None:
    aec = EchoCanceller()
    mic = np.random.default_rng(1).normal(0, 0.05, 1280).astype(np.float32)
    out, stats = aec.process(mic, np.zeros(1280, dtype=np.float32))
    assert np.array_equal(out, mic) and all(s.echo == 0.0 for s in stats)
    with pytest.raises(ValueError):
        aec.process(mic[:1000], np.zeros(1000, dtype=np.float32))


def test_echo_meter_tells_the_person_from_the_echo() -> None:
    robot = as_float32(clip("audio/tv_espeak_weather").samples)
    person = as_float32(clip("audio/wakeonly_piper").samples)
    x = np.concatenate([robot, robot])[: 2 * len(robot) // 1280 * 1280]
    near = np.zeros_like(x)
    at = len(robot)
    near[at : at + len(person)] = person
    mic = _echo(x) + near
    aec, meter = EchoCanceller(), EchoMeter()
    assert meter.judge(0.0, 1.0) == (0.0, True), "nothing heard, nothing played"
    for i in range(0, len(x), 1280):
        for j, s in enumerate(aec.process(mic[i : i + 1280], x[i : i + 1280])[1]):
            meter.add((i + (j + 1) * 256) / 16000, s)
    share, near_end = meter.judge(0.3, 1.2)
    assert share > 0.5 and not near_end, "the first playback: nothing proven yet, so it is the robot"
    share, near_end = meter.judge(3.5, 4.4)
    assert share > 0.5 and not near_end, "the converged echo alone"
    t = at / 16000
    share, near_end = meter.judge(t, t + len(person) / 16000)
    assert share > 0.5 and near_end, "the person talking over the robot"


# --- speech output ----------------------------------------------------------------------------------


class SlowTts(ToneSynthesizer):
    """Tone TTS that takes `delay` seconds and logs when each synthesis starts and ends."""

    def __init__(self, delay: float) -> None:
        super().__init__(seconds_per_char=0.01)
        self.delay = delay
        self.log: list[tuple[str, str, float]] = []
        self._lock = threading.Lock()

    def synthesize(self, text: str) -> AudioChunk:
        with self._lock:
            self.log.append(("synth-start", text, time.perf_counter()))
        time.sleep(self.delay)  # a model busy on its own thread
        chunk = super().synthesize(text)
        with self._lock:
            self.log.append(("synth-end", text, time.perf_counter()))
        return chunk


class PlayingSink(MemorySink):
    """A sink whose `write` returns once the chunk has been played (like a blocking device)."""

    def __init__(self, log: list[tuple[str, str, float]], seconds: float) -> None:
        super().__init__()
        self.log = log
        self.seconds = seconds
        self.stopped = asyncio.Event()
        self.playing = asyncio.Event()

    async def write(self, chunk: AudioChunk) -> None:
        self.log.append(("play-start", str(len(self.chunks)), time.perf_counter()))
        self.playing.set()
        await super().write(chunk)
        try:
            async with asyncio.timeout(self.seconds):
                await self.stopped.wait()
        except TimeoutError:
            pass
        self.log.append(("play-end", str(len(self.chunks) - 1), time.perf_counter()))

    def stop(self) -> None:
        super().stop()
        self.stopped.set()


async def test_synthesis_of_the_next_sentence_overlaps_playback() -> None:
    tts = SlowTts(delay=0.1)
    sink = PlayingSink(tts.log, seconds=0.3)
    executor = ModelExecutor("tts-test")
    speech = SpeechOutput(tts, sink, executor, queue_size=8)
    async with asyncio.TaskGroup() as group:
        task = group.create_task(speech.run())
        for text in ("One.", "Two.", "Three."):
            speech.say(text)
        assert speech.busy
        assert await speech.idle(timeout=10)
        task.cancel()
    await executor.aclose()
    times = {(kind, what): t for kind, what, t in tts.log}
    assert times[("synth-start", "Two.")] < times[("play-end", "0")], "sentence 2 synthesised while 1 played"
    assert times[("synth-start", "Three.")] < times[("play-end", "1")]
    assert [c.duration_s > 0 for c in sink.chunks] == [True, True, True]


async def test_interrupt_drops_everything_queued_at_once() -> None:
    tts = SlowTts(delay=0.05)
    sink = PlayingSink(tts.log, seconds=5.0)
    executor = ModelExecutor("tts-test")
    speech = SpeechOutput(tts, sink, executor, queue_size=8)
    async with asyncio.TaskGroup() as group:
        task = group.create_task(speech.run())
        for i in range(6):
            speech.say(f"Sentence {i}.", turn=1)
        async with asyncio.timeout(10):
            await sink.playing.wait()
        speech.interrupt()
        assert not speech.busy and sink.stop_count == 1
        speech.say("After the barge-in.", turn=2)
        assert await speech.idle(timeout=10)
        task.cancel()
    await executor.aclose()
    assert len(sink.chunks) == 2, "one sentence cut off, the rest never played, then the new one"
    assert speech.take_recording(2) is not None


async def test_withdraw_takes_back_only_what_has_not_started_playing() -> None:
    tts = SlowTts(delay=0.05)
    sink = PlayingSink(tts.log, seconds=0.2)
    executor = ModelExecutor("tts-test")
    speech = SpeechOutput(tts, sink, executor, queue_size=8)
    async with asyncio.TaskGroup() as group:
        task = group.create_task(speech.run())
        first = speech.say("Playing now.")
        async with asyncio.timeout(10):
            await sink.playing.wait()
        second = speech.say("On my way to the garage.")
        third = speech.say("I don't know where the garage is.")
        assert not speech.withdraw(first), "already playing"
        assert speech.withdraw(second) and not speech.withdraw(second)
        assert speech.say("   ") is None and not speech.withdraw(None)
        assert await speech.idle(timeout=10)
        assert third is not None and not speech.withdraw(third), "played"
        task.cancel()
    await executor.aclose()
    assert len(sink.chunks) == 2, "the first and the third sentence played, the withdrawn one never"


@pytest.mark.parametrize("width", [2, 4])
def test_wav_bytes_is_16_bit_pcm_whatever_the_sample_width(width: int) -> None:
    import io
    import wave

    from robovoice.audio.format import convert
    from robovoice.voice.utterance import wav_bytes

    t = np.arange(1600) / 16000
    x = AudioChunk((0.5 * np.sin(2 * np.pi * 440 * t)).astype(np.float32), MODEL_FORMAT.with_(width=4))
    chunk = x if width == 4 else convert(x, MODEL_FORMAT)
    with wave.open(io.BytesIO(wav_bytes(chunk))) as wf:
        assert (wf.getsampwidth(), wf.getframerate(), wf.getnframes()) == (2, 16000, 1600)
        samples = np.frombuffer(wf.readframes(1600), dtype="<i2").astype(np.float32) / 32768.0
    assert np.max(np.abs(samples - as_float32(x.samples))) < 1e-3  # the signal, not float bits read as int16
