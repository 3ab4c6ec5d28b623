"""The voice pipeline with the real models (openWakeWord, Silero VAD, Moonshine, Piper) from
WAV to tool call to the sim robot's state. The LLM is the fake vLLM server routing by
keywords (so the transcript must be right), or the embedded local model in one test."""

from __future__ import annotations

import io
import json
import wave
from pathlib import Path

import pytest

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, concat, convert, silence
from robovoice.audio.wav import read_wav
from robovoice.config import VoiceConfig
from robovoice.llm.base import Deadlines
from robovoice.llm.failover import FALLBACK_MESSAGE
from robovoice.llm.fake_server import CallbackReply, FakeOpenAIServer, Pacing, ScriptedCall, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.events import (
    BargedIn,
    RobotStopped,
    SentenceSpoken,
    TranscriptReady,
    UtteranceIgnored,
    VoiceTurnFinished,
    VoiceTurnStarted,
    WakeWordHeard,
    WakeWordRejected,
)
from robovoice.voice.models import VoiceModels

from .voice_kit import TEST_AUDIO, clip, keyword_router, voice_session, wait_until

pytestmark = [pytest.mark.integration, pytest.mark.timeout(180)]


def speak(models: VoiceModels, text: str) -> AudioChunk:
    """`text` in the robot's Piper voice, as a person in the room would say it (16 kHz)."""
    return convert(models.tts.synthesize(text), MODEL_FORMAT)


@pytest.fixture
def router(server: FakeOpenAIServer) -> FakeOpenAIServer:
    server.default = CallbackReply(keyword_router)
    return server


async def test_wake_word_then_command(voice_models: VoiceModels, router: FakeOpenAIServer,
                                      backend: OpenAICompatBackend) -> None:
    async with voice_session(voice_models, backend) as s:
        await s.say(clip("audio/wake_piper_projector"))
        done = await s.log.wait_for(VoiceTurnFinished, timeout=60)
        await s.settle()
        assert s.sim.state.projector_on
    assert len(s.log.of(WakeWordHeard)) == 1
    assert "projector" in s.log.of(TranscriptReady)[0].text.lower()
    assert done.result is not None and [c.name for c in done.result.calls] == ["set_projector_power"]
    assert [e.text for e in s.log.of(SentenceSpoken)] == ["The projector is now on."]  # its success phrase


@pytest.mark.parametrize("name", ["eval/nowake-02", "audio/cmd_piper_kitchen", "audio/tv_piper_news_babble10"])
async def test_no_wake_word_no_action(voice_models: VoiceModels, router: FakeOpenAIServer,
                                      backend: OpenAICompatBackend, name: str) -> None:
    async with voice_session(voice_models, backend) as s:
        await s.say(clip(name))
        await s.log.wait_for(UtteranceIgnored, timeout=30)
        await s.settle()
        state = s.sim.state
    assert router.requests == [] and not s.log.of(WakeWordHeard)
    assert not state.projector_on and state.nearest_place == "charging dock" and not state.moving


@pytest.mark.parametrize(
    ("name", "setup", "check"),
    [
        ("eval/wake-projector-off-1", "projector_on", "projector_off"),  # espeak-ng voice, pink noise, 20 dB SNR
        ("audio/wake_piper_kitchen_pink20", "", "kitchen"),  # Piper, pink noise, 20 dB SNR
        ("eval/wake-kitchen-1", "", "kitchen"),  # Piper (slower), babble, 10 dB SNR
        ("audio/wake_piper_battery_white10", "", "battery"),  # Piper, white noise, 10 dB SNR
    ],
)
async def test_command_in_noise(voice_models: VoiceModels, router: FakeOpenAIServer, backend: OpenAICompatBackend,
                                name: str, setup: str, check: str) -> None:
    async with voice_session(voice_models, backend, setup=setup) as s:
        await s.say(clip(name))
        done = await s.log.wait_for(VoiceTurnFinished, timeout=60)
        if check == "kitchen":
            await wait_until(lambda: s.sim.state.nearest_place == "kitchen" and not s.sim.state.moving, s.room)
        await s.settle()
        state = s.sim.state
    if check == "projector_off":
        assert not state.projector_on
    elif check == "battery":
        assert done.result is not None and [c.name for c in done.result.calls] == ["get_battery_state"]
    else:
        assert state.nearest_place == "kitchen"


async def test_stop_during_a_drive_while_the_model_is_busy(voice_models: VoiceModels, server: FakeOpenAIServer,
                                                           backend: OpenAICompatBackend) -> None:
    server.push(TextReply("Let me think about that.", pacing=Pacing(first_token_delay_s=90.0)))
    async with voice_session(voice_models, backend, sim_speed=1.0, setup="driving") as s:
        await s.say(clip("audio/wake_piper_battery_white10"))
        await s.log.wait_for(VoiceTurnStarted, timeout=30)
        await wait_until(lambda: len(server.requests) == 1, s.room)
        assert s.sim.state.moving
        await s.say(speak(voice_models, "Stop the robot!"), gap_s=0.5)  # no wake word: the robot moves
        stopped = await s.log.wait_for(RobotStopped, timeout=20)
        assert stopped.ok and not s.sim.state.moving
        await s.settle()
    assert s.log.of(VoiceTurnFinished)[0].cancelled
    assert stopped.latency_ms < 5000


async def test_barge_in_stops_the_speech_and_listens(voice_models: VoiceModels, server: FakeOpenAIServer,
                                                     backend: OpenAICompatBackend) -> None:
    long_reply = " ".join(f"This is sentence number {i} of a rather long answer." for i in range(1, 9))
    server.push(TextReply(long_reply), TextReply("Sure."))
    async with voice_session(voice_models, backend) as s:
        await s.say(clip("audio/wake_piper_battery_white10"))
        first = await s.log.wait_for(SentenceSpoken, timeout=60)
        await s.room.until(s.room.now + 2.0 + first.duration_s)  # a few sentences into the answer
        await s.say(clip("eval/wake-pose-2"), gap_s=0.0)  # "Hey Jarvis, where are you right now?"
        barge = await s.log.wait_for(BargedIn, timeout=20)
        second = await s.log.wait_for(VoiceTurnStarted, lambda e: e.turn == 2, timeout=30)
        await s.settle()
    assert barge.cancelled_turn == 1 and s.log.of(VoiceTurnFinished)[0].cancelled
    assert "where are you" in second.text.lower()
    answer_s = sum(e.duration_s for e in s.log.of(SentenceSpoken) if e.turn == 1)
    played_s = sum(chunk.duration_s for t, chunk in s.room.played if t < barge.at + 0.5)
    assert played_s < answer_s - 5.0, "the rest of the long answer was never played"
    assert s.room.speaker.stop_count >= 1


@pytest.mark.parametrize("echo_cancellation", [True, False], ids=["aec", "no-aec"])
async def test_the_robots_own_voice_does_not_wake_it(voice_models: VoiceModels, server: FakeOpenAIServer,
                                                      backend: OpenAICompatBackend, echo_cancellation: bool) -> None:
    # the robot's answer says the wake phrase, twice; its echo comes back into the microphone.
    # With echo cancellation the residual does not reach the (raised) wake threshold; without
    # it the microphone does hear "Hey Jarvis", and the playback's own detector rejects it.
    server.push(TextReply("To wake me up, say Hey Jarvis. Hey Jarvis, turn on the projector, for example. "
                          "Then I listen."))
    config = VoiceConfig(echo_cancellation=echo_cancellation)
    async with voice_session(voice_models, backend, config=config) as s:
        await s.say(clip("audio/wake_piper_battery_white10"))
        await s.log.wait_for(VoiceTurnFinished, timeout=60)
        await s.settle()
        assert not s.sim.state.projector_on
    assert len(s.log.of(WakeWordHeard)) == 1, "only the person's wake word"
    assert len(server.requests) == 1 and not s.log.of(BargedIn)
    if not echo_cancellation:
        assert len(s.log.of(WakeWordRejected)) >= 1, "the echo's wake phrase was heard and rejected"


async def test_a_video_calls_remote_voice_does_not_trigger(voice_models: VoiceModels, router: FakeOpenAIServer,
                                                            backend: OpenAICompatBackend) -> None:
    remote_wake = speak(voice_models, "Hey Jarvis, go to the kitchen.")
    remote_talk = speak(voice_models, "Mum, the children say hello. We will visit you on Sunday, "
                                      "and we bring a cake for your birthday.")
    person = clip("eval/wake-end-call-2")  # "Hey Jarvis, end the call." (Piper)
    async with voice_session(voice_models, backend, setup="in_call") as s:
        heard = s.room.play_remote(concat([remote_wake, silence(MODEL_FORMAT, 0.5)]))
        await heard.finished()
        await s.room.until(s.room.now + 1.0)
        assert router.requests == [] and not s.log.of(WakeWordHeard)
        s.room.play_remote(remote_talk)  # the remote keeps talking while the person speaks
        await s.say(person, gap_s=0.3)
        await s.log.wait_for(VoiceTurnFinished, timeout=60)
        await s.settle()
        state = s.sim.state
    assert s.log.of(WakeWordRejected), "the remote's wake phrase was heard and rejected"
    transcripts = [t.text for t in s.log.of(TranscriptReady)]  # over the remote's voice: say what was heard
    assert not state.in_call and state.nearest_place == "charging dock", transcripts
    result = s.log.of(VoiceTurnFinished)[0].result
    assert result is not None and [c.name for c in result.calls] == ["end_video_call"]


@pytest.mark.slow
async def test_wake_word_then_command_with_the_local_model(voice_models: VoiceModels) -> None:
    from robovoice.commands.common import warm_up
    from robovoice.llm.local import LocalLlamaBackend

    local = LocalLlamaBackend()
    try:
        async with voice_session(voice_models, local) as s:
            await warm_up(local, await s.tools.specs())
            await s.say(clip("audio/wake_piper_projector"))
            done = await s.log.wait_for(VoiceTurnFinished, timeout=120)
            await s.settle(timeout=120)
            assert s.sim.state.projector_on
    finally:
        await local.aclose()
    assert done.result is not None and "set_projector_power" in [c.name for c in done.result.calls]
    assert s.log.of(SentenceSpoken), "the model's answer was spoken"


async def test_fallback_is_spoken_when_the_backend_is_dead(voice_models: VoiceModels, unused_tcp_port: int,
                                                           tmp_path: Path) -> None:
    dead = OpenAICompatBackend(f"http://127.0.0.1:{unused_tcp_port}/v1", "nobody",
                               deadlines=Deadlines(connect_s=1.0, first_token_s=2.0))
    try:
        async with voice_session(voice_models, dead, output_dir=tmp_path) as s:
            await s.say(clip("audio/wake_piper_projector"))
            done = await s.log.wait_for(VoiceTurnFinished, timeout=60)
            await s.settle()
    finally:
        await dead.aclose()
    assert done.result is not None and done.result.fell_back and not s.sim.state.projector_on
    assert [e.text for e in s.log.of(SentenceSpoken)] == [FALLBACK_MESSAGE]
    answer = read_wav(tmp_path / "turn-01.wav")
    assert answer.duration_s > 2.0, "the fallback sentence was synthesised and played"


async def test_audio_native_backend_hears_the_utterance_itself(voice_models: VoiceModels,
                                                               server: FakeOpenAIServer) -> None:
    server.push(ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),)), TextReply("Done."))
    omni = OpenAICompatBackend(server.base_url, server.model, accepts_audio=True)
    no_stt = VoiceModels(wake=voice_models.wake, vad=voice_models.vad, stt=None, tts=voice_models.tts,
                         playback_wake=voice_models.playback_wake)
    spec = next(c for c in json.loads((TEST_AUDIO / "clips.json").read_text()) if c["id"] == "wake_piper_projector")
    try:
        async with voice_session(no_stt, omni) as s:
            await s.say(clip("audio/wake_piper_projector"))
            started = await s.log.wait_for(VoiceTurnStarted, timeout=30)
            await s.log.wait_for(VoiceTurnFinished, timeout=60)
            await s.settle()
            assert s.sim.state.projector_on
    finally:
        await omni.aclose()
    assert started.mode == "audio" and not s.log.of(TranscriptReady)
    fmt, data = server.requests[0].audio_inputs()[0]
    with wave.open(io.BytesIO(data)) as wf:
        assert (fmt, wf.getnchannels(), wf.getsampwidth(), wf.getframerate()) == ("wav", 1, 2, 16000)
        seconds = wf.getnframes() / wf.getframerate()
    speech = spec["speech_end_s"] - spec["speech_start_s"]
    assert speech - 0.1 <= seconds <= speech + 0.3 + 0.2 + 0.2  # + pre-roll, post-roll, VAD frame rounding


def test_loaded_voice_says_its_fixed_phrases_from_memory(voice_models: VoiceModels) -> None:
    from robovoice.audio.tts_cache import CachedSynthesizer
    from robovoice.voice.models import fixed_phrases

    tts = voice_models.tts
    assert isinstance(tts, CachedSynthesizer)
    hits = tts.hits
    for phrase in fixed_phrases():  # synthesised while the models loaded
        assert len(tts.synthesize(phrase).samples) > 0
    assert tts.hits == hits + len(fixed_phrases())
