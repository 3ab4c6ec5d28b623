"""Using the end-of-turn silence with fakes: the endpointer's early end, the listener's pause
that allows it, the speculator's decisions, and the whole pipeline (a backend that records
its prefills; the sim robot over MCP)."""

from __future__ import annotations

import asyncio
from collections.abc import Sequence

import numpy as np

from robovoice.assistant.events import ToolCalled
from robovoice.audio.fakes import EnergyVAD, ToneWakeDetector
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, silence
from robovoice.audio.stt import Transcript
from robovoice.audio.vad import Endpointer, EndpointerConfig, SpeechEnded, SpeechSegmenter, SpeechStarted
from robovoice.audio.wake import WakeDecider, WakeWordSpotter
from robovoice.config import VoiceConfig
from robovoice.llm.base import ChatMessage, ToolSpec
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedCall, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.config import PipelineConfig
from robovoice.voice.events import VoiceTurnStarted
from robovoice.voice.listener import HeardPause, HeardUtterance, Listener
from robovoice.voice.models import VoiceModels
from robovoice.voice.speculate import SpeculationConfig, Speculator

from .voice_kit import SettableTranscriber, babble, join, tone, voice_session

F = 0.032


def feed(ep: Endpointer, probs: list[float]) -> list[tuple[int, SpeechStarted | SpeechEnded]]:
    out = []
    for k, p in enumerate(probs):
        out += [(k, e) for e in ep.update(p, np.zeros(512, dtype=np.int16), k * F)]
    return out


# --- the endpointer ------------------------------------------------------------------------------


def test_an_allowed_early_end_ends_after_the_shorter_silence() -> None:
    ep = Endpointer(EndpointerConfig(end_silence_s=0.5))
    events = feed(ep, [0.1] * 5 + [0.9] * 30)
    assert [type(e) for _, e in events] == [SpeechStarted]
    ep.allow_early_end(5 * F, 35 * F, 0.3)  # the words up to the pause at frame 35 are complete
    events = feed_from(ep, 35, [0.1] * 20)
    [(k, ended)] = events
    assert isinstance(ended, SpeechEnded) and ended.early
    assert k == 35 + 9  # 10 quiet frames = 0.32 s >= 0.3 s (the full rule needs 16)
    assert ended.end == 35 * F


def test_speech_after_the_pause_voids_the_early_end() -> None:
    ep = Endpointer(EndpointerConfig(end_silence_s=0.5))
    feed(ep, [0.1] * 5 + [0.9] * 30)
    ep.allow_early_end(5 * F, 35 * F, 0.3)
    # 6 quiet frames (0.19 s), speech again ("go to the ... kitchen"), then silence
    events = feed_from(ep, 35, [0.1] * 6 + [0.9] * 10 + [0.1] * 20)
    [(k, ended)] = events
    assert isinstance(ended, SpeechEnded) and not ended.early
    assert k == 51 + 15  # the full 0.5 s after the last word
    assert ended.end == 51 * F


def test_an_early_end_for_another_utterance_is_ignored() -> None:
    ep = Endpointer(EndpointerConfig(end_silence_s=0.5))
    feed(ep, [0.1] * 5 + [0.9] * 30)
    ep.allow_early_end(1.0, 35 * F, 0.3)  # not this utterance's onset
    [(k, ended)] = feed_from(ep, 35, [0.1] * 20)
    assert isinstance(ended, SpeechEnded) and not ended.early and k == 35 + 15


def feed_from(ep: Endpointer, first: int, probs: list[float]) -> list[tuple[int, SpeechStarted | SpeechEnded]]:
    out = []
    for k, p in enumerate(probs, start=first):
        out += [(k, e) for e in ep.update(p, np.zeros(512, dtype=np.int16), k * F)]
    return out


# --- the listener: a pause carries the early end ---------------------------------------------------


def run_listener(audio: AudioChunk, early_s: float | None) -> tuple[HeardUtterance, float]:
    """The utterance the listener closes, and the stream time of the chunk that closed it;
    with `early_s`, every pause allows an early end at once (an instant transcript)."""
    cfg = PipelineConfig.from_config()
    listener = Listener(WakeWordSpotter(ToneWakeDetector(), WakeDecider(cfg.wake)),
                        SpeechSegmenter(EnergyVAD(), Endpointer(cfg.endpointer)), None, cfg.echo,
                        playback_tail_s=0.3)
    step = 1280
    for i in range(0, len(audio.samples), step):
        heard = listener.process(AudioChunk(audio.samples[i : i + step], MODEL_FORMAT, i / MODEL_FORMAT.rate))
        for event in heard.events:
            if isinstance(event, HeardPause) and early_s is not None:
                event.end_early(early_s)
            if isinstance(event, HeardUtterance):
                return event, heard.now
    raise AssertionError("no utterance ended")


def test_the_listener_ends_early_only_when_the_pause_allows_it() -> None:
    said = join(silence(MODEL_FORMAT, 0.3), babble(1.2), silence(MODEL_FORMAT, 1.0))
    full, full_at = run_listener(said, None)
    early, early_at = run_listener(said, 0.3)
    assert not full.early and early.early
    assert early.end == full.end  # the same words, the same last word
    assert 0.15 <= full_at - early_at <= 0.25  # 0.2 s of silence saved (at 80 ms chunk granularity)
    assert full_at - full.end >= 0.5 and early_at - early.end >= 0.3


# --- the speculator ---------------------------------------------------------------------------------


class RecordingBackend(OpenAICompatBackend):
    """The fake server's backend, plus a `prefill` that records what it was asked to prefill and
    how many pipeline events had been seen by then."""

    def __init__(self, server: FakeOpenAIServer) -> None:
        super().__init__(server.base_url, server.model)
        self.prefills: list[tuple[list[ChatMessage], list[str], bool]] = []
        self.seen: Sequence[object] = ()  # the pipeline's event log, once the session runs
        self.seen_at_prefill: list[int] = []

    async def prefill(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec], *, decode: bool = True
    ) -> None:
        self.prefills.append((list(messages), [t.name for t in tools], decode))
        self.seen_at_prefill.append(len(self.seen))


class FakeAssistant:
    def __init__(self, backend: object) -> None:
        self.backend = backend
        self.asked: list[str] = []

    async def first_request(self, text: str) -> tuple[list[ChatMessage], list[ToolSpec]]:
        self.asked.append(text)
        return [ChatMessage("system", "s"), ChatMessage("user", text)], [ToolSpec("navigate_to", "go", {})]


def speculation(**voice: object) -> SpeculationConfig:
    """The speculation settings of a ``[voice]`` section with these keys."""
    return SpeculationConfig.from_config(VoiceConfig.model_validate(voice))


def pause_recorder() -> tuple[HeardPause, list[float]]:
    allowed: list[float] = []
    return HeardPause(0.0, 1.0, silence(MODEL_FORMAT, 0.1), allowed.append), allowed


async def follow(text: str, *, command: bool = True, config: SpeculationConfig | None = None,
                 cancelled: bool = False) -> tuple[list[float], FakeAssistant, list[tuple[list[ChatMessage], list[str],
                                                                                         bool]]]:
    async with FakeOpenAIServer() as server:
        backend = RecordingBackend(server)
        assistant = FakeAssistant(backend)
        speculator = Speculator(config or speculation(), assistant, "hey jarvis")  # type: ignore[arg-type]  # a stand-in with first_request

        async def transcribe() -> tuple[Transcript, float]:
            await asyncio.sleep(0.01)
            return Transcript(text, 1.0), 10.0

        task = asyncio.create_task(transcribe())
        if cancelled:
            task.cancel()
        pause, allowed = pause_recorder()
        await speculator.follow(pause, task, woken=True, command=command)
        await backend.aclose()
        return allowed, assistant, backend.prefills


async def test_a_complete_request_allows_the_early_end_and_is_prefilled() -> None:
    allowed, assistant, prefills = await follow("Hey Jarvis, go to the kitchen.")
    assert allowed == [0.3]
    assert assistant.asked == ["go to the kitchen."]  # the wake phrase removed, as the real turn does
    [(messages, tools, decode)] = prefills
    assert messages[-1].text == "go to the kitchen." and tools == ["navigate_to"] and decode


async def test_go_to_the_keeps_the_full_silence_but_is_still_prefilled() -> None:
    allowed, assistant, prefills = await follow("Hey Jarvis, go to the")
    assert allowed == [] and assistant.asked == ["go to the"] and len(prefills) == 1


async def test_no_early_end_when_switched_off_or_after_a_stop_no_prefill_for_a_stop() -> None:
    allowed, _, prefills = await follow("Go to the kitchen.", config=speculation(early_end=False,
                                                                                    speculative_prefill=False))
    assert (allowed, prefills) == ([], [])
    # a stop goes to the stop tool, not the model; it acts at the pause (`check_pause`), and what
    # may follow it ("stop there, and then go back to your charger") is still heard
    allowed, _, prefills = await follow("Hey Jarvis, stop there.")
    assert allowed == [] and prefills == []
    allowed, _, prefills = await follow("stop", command=False)
    assert allowed == [] and prefills == []
    allowed, _, _ = await follow("Hey Jarvis, stop the call.")  # not a stop phrase: a complete request
    assert allowed == [0.3]


async def test_a_dropped_transcription_does_nothing() -> None:
    allowed, assistant, prefills = await follow("go to the kitchen", cancelled=True)
    assert (allowed, assistant.asked, prefills) == ([], [], [])


# --- the whole pipeline ---------------------------------------------------------------------------


async def test_pipeline_prefills_in_the_silence_and_nothing_reaches_the_robot_before_the_end_of_turn(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer
) -> None:
    server.push(ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),)), TextReply("It is on."))
    transcriber.text = "Hey Jarvis, turn on the projector."
    backend = RecordingBackend(server)
    async with voice_session(fakes, backend, speed=2.0) as s:
        backend.seen = s.log.events
        await s.say(join(tone(0.5), babble(1.0)), gap_s=0.8)
        started = await s.log.wait_for(VoiceTurnStarted)
        await s.log.wait_for(ToolCalled)
        await s.settle()
        speculator = s.pipeline.router.speculator
    await backend.aclose()
    [(messages, tools, _)] = backend.prefills
    assert messages[-1].text == started.text == "turn on the projector."
    assert "set_projector_power" in tools
    # the prefill came before the turn started, and no tool had been called by then
    [at_prefill] = backend.seen_at_prefill
    before = s.log.events[:at_prefill]
    assert not [e for e in before if isinstance(e, (ToolCalled, VoiceTurnStarted))]
    assert speculator.stats.early_ends == 1 and speculator.stats.prefills == 1
    assert s.sim.state.projector_on


async def test_pipeline_a_changed_transcript_prefills_a_guess_the_turn_does_not_use(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer
) -> None:
    server.push(TextReply("Done."))
    # at the short pause the words are complete ("turn on the projector"), then speech goes on
    transcriber.by_length = lambda seconds: ("Hey Jarvis, turn on the projector and the light." if seconds > 2.0
                                             else "Hey Jarvis, turn on the projector.")
    said = join(tone(0.5), babble(1.0), silence(MODEL_FORMAT, 0.2), babble(1.0, seed=3))
    backend = RecordingBackend(server)
    async with voice_session(fakes, backend, speed=2.0) as s:
        await s.say(said)
        started = await s.log.wait_for(VoiceTurnStarted)
        await s.settle()
    await backend.aclose()
    assert started.text == "turn on the projector and the light."
    guesses = [messages[-1].text for messages, _, _ in backend.prefills]
    assert guesses[0] == "turn on the projector."  # the guess at the short pause: not what the turn sent
    said_to_model = [m["content"] for m in server.requests[0].messages if m["role"] == "user"]
    assert said_to_model[0] == "turn on the projector and the light."
