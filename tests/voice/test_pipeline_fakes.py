"""The voice pipeline end to end with model fakes (tone = wake word, noise = speech,
a settable transcript, tone TTS), the sim robot over MCP, and the fake vLLM server."""

from __future__ import annotations

import io
import wave
from pathlib import Path

import numpy as np
import pytest

from robovoice.assistant.events import BackendFailed, ToolCalled, ToolReturned
from robovoice.audio.format import MODEL_FORMAT, silence
from robovoice.config import VoiceConfig
from robovoice.llm.base import Deadlines
from robovoice.llm.failover import FALLBACK_MESSAGE
from robovoice.llm.fake_server import FakeOpenAIServer, Pacing, ScriptedCall, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.events import (
    BargedIn,
    RobotStopped,
    SentenceSpoken,
    StopHeard,
    TranscriptReady,
    UtteranceIgnored,
    VoiceTurnFinished,
    VoiceTurnStarted,
    WakeWordHeard,
    WakeWordRejected,
)
from robovoice.voice.models import VoiceModels
from robovoice.voice.room import SimulatedRoom
from robovoice.voice.vocabulary import STOP_HINT

from .voice_kit import SettableTranscriber, babble, fake_models, join, tone, voice_session, wait_until, wake_command

pytestmark = pytest.mark.timeout(90)


async def test_wake_word_then_command_calls_the_tool_and_speaks(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer,
    backend: OpenAICompatBackend, tmp_path: Path,
) -> None:
    server.push(ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),)))
    transcriber.text = "Hey Jarvis, turn on the projector."
    async with voice_session(fakes, backend, speed=2.0, output_dir=tmp_path) as s:
        await s.say(wake_command())
        done = await s.log.wait_for(VoiceTurnFinished)
        await s.settle()
        assert s.sim.state.projector_on
    assert [e.text for e in s.log.of(TranscriptReady)] == ["turn on the projector."]
    assert server.requests[0].last_user_text == "turn on the projector."
    # speech-to-text was told the words to expect: the wake phrase and the robot's tools
    assert transcriber.hints and all(h.startswith("Hey Jarvis. ") for h in transcriber.hints)
    assert "set projector power" in transcriber.hints[-1] and "stop robot" in transcriber.hints[-1]
    assert not done.cancelled and done.result is not None
    assert [c.name for c in done.result.calls] == ["set_projector_power"]
    spoken = s.log.of(SentenceSpoken)
    assert [e.text for e in spoken] == ["The projector is now on."]  # the tool's phrase: one model step
    marks = done.latency_ms
    for stage in ("endpoint", "transcript", "first_token", "tool_call:set_projector_power",
                  "tool_result:set_projector_power", "first_sentence", "first_audio"):
        assert stage in marks, stage
    assert marks["endpoint"] <= marks["transcript"] <= marks["first_token"] <= marks["first_sentence"]
    assert marks["first_sentence"] <= marks["first_audio"]
    with wave.open(str(tmp_path / "turn-01.wav")) as wf:
        assert wf.getnframes() / wf.getframerate() == pytest.approx(spoken[0].duration_s, abs=0.01)


async def test_speech_without_wake_word_does_nothing(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    transcriber.text = "turn on the projector"
    async with voice_session(fakes, backend, speed=2.0) as s:
        await s.say(babble(1.5))
        ignored = await s.log.wait_for(UtteranceIgnored)
        await s.settle()
    assert ignored.reason == "no_wake_word"
    assert server.requests == [] and transcriber.calls == 0
    assert not s.sim.state.projector_on


async def test_a_near_miss_of_the_wake_phrase_calling_someone_else_does_nothing(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    """The wake model fired on "Hey Charlie" (audio test v4's espeak voice drove to the front
    door): the transcript shows the person called someone else, and nothing is done."""
    transcriber.text = "Hey Charlie, go along to the front door, will you?"
    async with voice_session(fakes, backend, speed=2.0) as s:
        await s.say(wake_command())
        ignored = await s.log.wait_for(UtteranceIgnored)
        await s.settle()
    assert ignored.reason == "addressed_elsewhere" and server.requests == []
    assert not s.sim.state.moving and not s.log.of(VoiceTurnStarted)


UNSURE = VoiceConfig(wake_threshold=0.995, wake_unsure_threshold=0.5)  # the fake wake tone scores 0.99: unsure


@pytest.mark.parametrize(("heard", "acts"), [("Hey Jarvis, turn on the projector.", True),
                                             ("Hey Travis, turn on the projector.", False)])
async def test_an_unsure_wake_word_counts_only_when_the_transcript_names_the_robot(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend,
    heard: str, acts: bool,
) -> None:
    """A wake score under the threshold (espeak-ng voices in noise score 0.1-0.5): the robot
    acts if the words say "Jarvis", and takes "Hey Travis, ..." for talk to somebody else."""
    server.push(ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),)))
    transcriber.text = heard
    async with voice_session(fakes, backend, speed=2.0, config=UNSURE) as s:
        await s.say(wake_command())
        if acts:
            await s.log.wait_for(VoiceTurnFinished)
        else:
            ignored = await s.log.wait_for(UtteranceIgnored)
            assert ignored.reason == "wake_unconfirmed" and ignored.text == heard
        await s.settle()
    assert [(e.sure, round(e.score, 2)) for e in s.log.of(WakeWordHeard)] == [(False, 0.99)]
    assert s.sim.state.projector_on is acts
    assert len(server.requests) == (1 if acts else 0)


async def test_an_unsure_wake_word_while_moving_never_loses_a_stop(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    """Audio test v14: an unsure wake made a stop while driving a command, whose transcript
    did not name the robot, and the drive went on; its words are checked for a stop."""
    transcriber.text = "Stop right there!"
    async with voice_session(fakes, backend, speed=2.0, sim_speed=2.0, setup="driving", config=UNSURE) as s:
        assert s.sim.state.moving
        await s.say(wake_command())
        stopped = await s.log.wait_for(RobotStopped, timeout=10)
        await s.settle()
    assert stopped.ok and not s.sim.state.moving
    assert [e.sure for e in s.log.of(WakeWordHeard)] == [False] and server.requests == []


async def test_an_unsure_wake_word_while_moving_that_names_the_robot_is_a_command(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    """Audio test v15: "Hey Jarvis, stop there, then head to the bathroom instead" (wake score
    0.42) while driving was taken for a stop alone; its words name the robot: a command."""
    server.push(ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),)))
    transcriber.text = "Hey Jarvis, switch the projector on."
    async with voice_session(fakes, backend, speed=2.0, sim_speed=2.0, setup="driving", config=UNSURE) as s:
        await s.say(wake_command())
        await s.log.wait_for(VoiceTurnFinished, timeout=20)
        await s.settle()
    assert s.sim.state.projector_on and len(server.requests) == 1
    assert [e.sure for e in s.log.of(WakeWordHeard)] == [False]


async def test_unsure_wake_words_are_off_with_a_zero_threshold(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    transcriber.text = "Hey Jarvis, turn on the projector."
    off = UNSURE.model_copy(update={"wake_unsure_threshold": 0.0})
    async with voice_session(fakes, backend, speed=2.0, config=off) as s:
        await s.say(wake_command())
        ignored = await s.log.wait_for(UtteranceIgnored)
        await s.settle()
    assert ignored.reason == "no_wake_word" and transcriber.calls == 0
    assert s.log.of(WakeWordHeard) == [] and server.requests == []


async def test_a_command_longer_than_the_wake_timeout_is_still_a_command(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    """Audio test v10: a 6.7 s command ended after its wake word's 6 s timeout, and was ignored."""
    server.push(TextReply("All right."))
    transcriber.text = "Hey Jarvis, go to the bedroom, no, sorry, the kitchen, and then ring Clara."
    async with voice_session(fakes, backend, speed=2.0) as s:
        await s.say(wake_command(6.5))
        started = await s.log.wait_for(VoiceTurnStarted, timeout=20)
        await s.settle()
    assert started.text.startswith("go to the bedroom")
    assert [e.reason for e in s.log.of(UtteranceIgnored) if e.start < started.audio_s] == []


async def test_wake_word_alone_waits_for_the_command(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(TextReply("It is quarter past ten."))
    async with voice_session(fakes, backend, speed=2.0) as s:
        transcriber.text = "Hey Jarvis."
        await s.say(tone(0.5))
        ignored = await s.log.wait_for(UtteranceIgnored)
        assert ignored.reason == "wake_only"
        transcriber.text = "what time is it?"
        await s.say(babble(1.0), gap_s=1.0)
        started = await s.log.wait_for(VoiceTurnStarted)
        await s.settle()
    assert started.text == "what time is it?"
    assert [e.text for e in s.log.of(SentenceSpoken)] == ["It is quarter past ten."]


async def test_spoken_stop_stops_a_drive_while_the_model_is_busy(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    # the model takes a minute to answer: the stop must not wait for it
    server.push(TextReply("Let me think.", pacing=Pacing(first_token_delay_s=60.0)))
    async with voice_session(fakes, backend, speed=2.0, sim_speed=2.0, setup="driving") as s:
        assert s.sim.state.moving
        transcriber.text = "Hey Jarvis, tell me a long story."
        await s.say(wake_command())
        await s.log.wait_for(VoiceTurnStarted)
        await wait_until(lambda: len(server.requests) == 1, s.room)
        transcriber.text = "Stop!"
        await s.say(babble(0.5))  # no wake word: the robot is moving
        stopped = await s.log.wait_for(RobotStopped, timeout=10)
        assert stopped.ok and not s.sim.state.moving
        finished = await s.log.wait_for(VoiceTurnFinished, timeout=10)
        await s.settle()
    heard = s.log.of(StopHeard)[0]
    assert heard.cancelled_turn == finished.turn and finished.cancelled
    assert stopped.latency_ms < 3000  # end of "stop" -> stop tool answered, the model still silent
    # timed from the last word too: the end-of-turn silence comes on top of the decision's figure
    assert stopped.from_last_word_ms is not None and stopped.from_last_word_ms > stopped.latency_ms
    assert [e.text for e in s.log.of(SentenceSpoken) if e.kind == "stop"] == ["Stopped."]
    assert transcriber.hints[-1] == STOP_HINT  # the stop check listens for stop words only


async def test_a_stop_acts_at_its_first_pause_without_waiting_for_the_end_of_the_utterance(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    """Issue 12: a stop is decided at the first quiet frame after it, from the speculative
    transcript, not after the end-of-turn silence; words after it change nothing, and the
    utterance's own end does not stop (or say "Stopped.") a second time."""
    async with voice_session(fakes, backend, speed=2.0, sim_speed=1.0, setup="driving") as s:
        assert s.sim.state.moving
        transcriber.text = "Stop!"
        await s.say(join(babble(0.5), silence(MODEL_FORMAT, 0.25), babble(1.0, seed=5)))
        stopped = await s.log.wait_for(RobotStopped, timeout=10)
        await s.settle()
    assert stopped.ok and not s.sim.state.moving
    heard = s.log.of(StopHeard)
    assert len(heard) == 1
    # the utterance the stop was heard in ended 1.25 s after the pause the stop acted at; its end
    # found the robot standing (no stop check then) or the stop already made
    [said] = [e for e in s.log.of(UtteranceIgnored) if e.start < heard[0].at]
    assert said.reason in ("no_wake_word", "stopped_at_pause") and heard[0].at < said.end - 0.9, (heard, said)
    assert [e.text for e in s.log.of(SentenceSpoken) if e.kind == "stop"] == ["Stopped."]
    # the robot stopped at the pause but said so only once the person had finished
    [spoken] = [i for i, e in enumerate(s.log.events) if isinstance(e, SentenceSpoken) and e.kind == "stop"]
    assert s.log.events.index(said) < spoken


async def test_what_follows_an_addressed_stop_still_reaches_the_model(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    """Audio test v9's "Hey Jarvis, stop there, and then go back to your charger.": the stop acts
    at the pause, the complete-looking "Stop there." does not end the utterance early, and the
    whole request still goes to the model, whose dock call is not cancelled by that stop."""
    server.push(ToolCallReply((ScriptedCall("return_to_dock", {}),)))
    # the first pause's transcript (wake tone + the first words) is the stop, a longer one is all
    # of it; later short ones (the robot's own "Stopped.") are heard as nothing
    first = iter(["Hey Jarvis, stop there."])
    transcriber.by_length = lambda seconds: (
        next(first, "") if seconds < 1.5 else "Hey Jarvis, stop there, and then go back to your charger.")
    async with voice_session(fakes, backend, speed=2.0, sim_speed=2.0, setup="driving") as s:
        assert s.sim.state.moving
        # 0.4 s between: longer than the 300 ms early end, shorter than the 500 ms end of turn
        await s.say(join(wake_command(0.5), silence(MODEL_FORMAT, 0.4), babble(1.2, seed=3)))
        stopped = await s.log.wait_for(RobotStopped, timeout=10)
        finished = await s.log.wait_for(VoiceTurnFinished, timeout=30)
        await s.settle()
    assert stopped.ok
    [heard] = s.log.of(StopHeard)
    [started] = s.log.of(VoiceTurnStarted)
    assert started.text == "stop there, and then go back to your charger."
    assert heard.cancelled_turn is None  # the stop came before the command turn, and spared it
    assert not finished.cancelled and finished.result is not None
    assert [c.name for c in finished.result.calls] == ["return_to_dock"]
    # "Stopped." waited for the end of the person's sentence, so it was not said over the rest
    [spoken] = [i for i, e in enumerate(s.log.events) if isinstance(e, SentenceSpoken) and e.kind == "stop"]
    assert s.log.events.index(started) < spoken
    assert server.requests and any(m.get("content") == started.text for m in server.requests[0].messages)


async def test_stop_cancels_the_drive_the_voice_started(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(ToolCallReply((ScriptedCall("navigate_to", {"target": "bedroom"}),)),
                TextReply("I stopped."))
    async with voice_session(fakes, backend, speed=2.0, sim_speed=1.0) as s:
        transcriber.text = "Hey Jarvis, go to the bedroom."
        await s.say(wake_command())
        await s.log.wait_for(ToolCalled)
        await wait_until(lambda: s.sim.state.moving, s.room)
        transcriber.text = "Stop the robot."
        await s.say(babble(0.6))
        stopped = await s.log.wait_for(RobotStopped, timeout=10)
        await s.settle()
        assert stopped.ok and not s.sim.state.moving
    assert s.log.of(VoiceTurnFinished)[0].cancelled
    progress = [e.text for e in s.log.of(SentenceSpoken) if e.kind == "progress"]
    assert progress[:1] == ["On my way to the bedroom."]


async def test_long_action_gives_throttled_progress_then_the_result(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),)))
    config = VoiceConfig(progress_interval_s=1.0)
    async with voice_session(fakes, backend, speed=2.0, sim_speed=4.0, config=config) as s:
        transcriber.text = "Hey Jarvis, go to the kitchen."
        await s.say(wake_command())
        await s.log.wait_for(ToolReturned, timeout=60)
        await s.settle()
    assert s.sim.state.nearest_place == "kitchen"
    spoken = s.log.of(SentenceSpoken)
    progress = [e.text for e in spoken if e.kind == "progress"]
    assert progress[0] == "On my way to the kitchen."
    assert 2 <= len(progress) <= 8 and all(p.startswith("Still on my way") for p in progress[1:])
    assert spoken[-1].text == "I am in the kitchen now." and spoken[-1].kind == "reply"  # the drive's phrase


async def test_fallback_is_spoken_when_no_backend_answers(
    fakes: VoiceModels, transcriber: SettableTranscriber, unused_tcp_port: int
) -> None:
    dead = OpenAICompatBackend(f"http://127.0.0.1:{unused_tcp_port}/v1", "nobody",
                               deadlines=Deadlines(connect_s=1.0, first_token_s=2.0))
    try:
        async with voice_session(fakes, dead, speed=2.0) as s:
            transcriber.text = "Hey Jarvis, turn on the projector."
            await s.say(wake_command())
            await s.log.wait_for(VoiceTurnFinished)
            await s.settle()
    finally:
        await dead.aclose()
    assert len(s.log.of(BackendFailed)) == 1
    assert [e.text for e in s.log.of(SentenceSpoken)] == [FALLBACK_MESSAGE]
    assert not s.sim.state.projector_on


async def test_audio_capable_backend_gets_the_utterance_as_wav(server: FakeOpenAIServer) -> None:
    server.push(ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),)), TextReply("Done."))
    omni = OpenAICompatBackend(server.base_url, server.model, accepts_audio=True)
    models = fake_models()
    models = type(models)(wake=models.wake, vad=models.vad, stt=None, tts=models.tts,
                          playback_wake=models.playback_wake)
    command = wake_command(1.2)
    try:
        async with voice_session(models, omni, speed=2.0) as s:
            await s.say(command)
            started = await s.log.wait_for(VoiceTurnStarted)
            await s.log.wait_for(VoiceTurnFinished)
            await s.settle()
    finally:
        await omni.aclose()
    assert started.mode == "audio" and started.text == ""
    assert s.sim.state.projector_on
    audio = server.requests[0].audio_inputs()
    assert len(audio) == 1 and audio[0][0] == "wav"
    with wave.open(io.BytesIO(audio[0][1])) as wf:
        assert (wf.getnchannels(), wf.getsampwidth(), wf.getframerate()) == (1, 2, 16000)
        seconds = wf.getnframes() / wf.getframerate()
    # the utterance: the speech, 0.3 s of pre-roll before it, at most 0.2 s after it
    assert command.duration_s <= seconds <= command.duration_s + 0.55
    assert seconds == pytest.approx(started.audio_s, abs=1e-3)
    assert len(server.requests[1].audio_inputs()) == 1, "the tool round of the same turn still has the audio"


async def test_wake_word_while_speaking_barges_in(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    # long enough that the barge-in lands inside it even when a loaded machine delays the test
    long_reply = " ".join(f"This is sentence number {i} of a rather long answer." for i in range(1, 25))
    server.push(TextReply(long_reply), TextReply("Sure, the projector is on."))
    async with voice_session(fakes, backend, speed=2.0) as s:
        transcriber.text = "Hey Jarvis, tell me something."
        await s.say(wake_command())
        opening = await s.log.wait_for(SentenceSpoken)
        # talk over the robot once its first sentence has sounded whole, not over its very first
        # sound: the echo canceller cannot learn the echo path while the person talks over the
        # first playback it ever hears (the residual then masks the wake tone, as happened under
        # load), and the first wake word's refractory period is over by then
        await wait_until(lambda: robot_sound_start(s.room) is not None, s.room)
        sounding = robot_sound_start(s.room)
        assert sounding is not None
        await s.room.until(sounding + opening.duration_s)
        transcriber.text = "Hey Jarvis, never mind."
        await s.say(wake_command(0.6), gap_s=0.0)
        barge = await s.log.wait_for(BargedIn)
        await s.log.wait_for(VoiceTurnStarted, lambda e: e.turn == 2)
        await s.settle()
    assert barge.cancelled_turn == 1
    first = s.log.of(VoiceTurnFinished)[0]
    assert first.turn == 1 and first.cancelled
    assert s.room.speaker.stop_count >= 1
    # SentenceSpoken means "handed to the speaker", which queues without limit; what was cut
    # short is what sounded in the room (turn 2's short answer included, still far less), not
    # the silence a lagging pipeline's speaker starts with (`RoomSpeaker.write`)
    queued_first = [e for e in s.log.of(SentenceSpoken) if e.turn == 1]
    sounded_s = sum(np.count_nonzero(chunk.samples) for _, chunk in s.room.played) / MODEL_FORMAT.rate
    assert queued_first and sounded_s < sum(e.duration_s for e in queued_first) / 2, "the long answer was cut short"
    assert s.log.of(WakeWordHeard)[-1].during_playback


def robot_sound_start(room: SimulatedRoom) -> float | None:
    """When the robot's speaker first sounded (stream time), None while it has not."""
    for t0, chunk in room.played:
        sounding = np.flatnonzero(chunk.samples)
        if sounding.size:
            return t0 + int(sounding[0]) / MODEL_FORMAT.rate
    return None


async def test_remote_participant_saying_the_wake_word_is_ignored(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(ToolCallReply((ScriptedCall("end_video_call", {}),)), TextReply("The call has ended."))
    async with voice_session(fakes, backend, speed=2.0, setup="in_call") as s:
        transcriber.text = "Hey Jarvis, go to the kitchen."
        remote = s.room.play_remote(wake_command(1.0))  # through the robot's speaker
        await remote.finished()
        await s.room.until(s.room.now + 1.0)
        assert server.requests == [] and s.log.of(WakeWordRejected)
        # the person in the room can still end the call, while the remote keeps talking
        s.room.play_remote(babble(3.0, seed=5))
        transcriber.text = "Hey Jarvis, end the call."
        await s.say(wake_command(0.8))
        await s.log.wait_for(VoiceTurnFinished)
        await s.settle()
    assert not s.sim.state.in_call
    assert [r.last_user_text for r in server.requests][:1] == ["end the call."]


async def test_an_answer_to_the_robots_question_needs_no_wake_word(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(TextReply("Which room do you mean?"),
                ToolCallReply((ScriptedCall("navigate_to", {"target": "bedroom"}),)))
    async with voice_session(fakes, backend, speed=2.0, sim_speed=10.0) as s:
        transcriber.text = "Hey Jarvis, go to the other room."
        await s.say(wake_command())
        await s.log.wait_for(VoiceTurnFinished)
        await s.settle()
        transcriber.text = "The bedroom."
        await s.say(babble(0.8), gap_s=0.8)  # no wake word: it answers the question
        second = await s.log.wait_for(VoiceTurnStarted, lambda e: e.turn == 2)
        await s.log.wait_for(VoiceTurnFinished, lambda e: e.turn == 2, timeout=60)
        await s.settle()
        transcriber.text = "And the kitchen after that."
        third_at = s.room.now
        await s.say(babble(0.8), gap_s=2.0)  # the robot made a statement: no follow-up now
        # (an utterance's start is rounded to the VAD's 32 ms frame: speech starting at `third_at` may
        # be dated up to a frame before it)
        ignored = await s.log.wait_for(UtteranceIgnored,
                                       lambda e: e.reason != "own_voice" and e.start >= third_at - 0.05)
        await s.settle()
    assert second.follow_up and second.text == "The bedroom."
    assert s.sim.state.nearest_place == "bedroom"
    assert ignored.reason == "no_wake_word" and len(server.requests) == 2  # the drive's phrase answered it
    # whatever of the robot's own answers came back as echo was recognised as its own voice, or,
    # heard while it drove, checked for a stop and found none (the fake transcriber cannot tell
    # the robot's words from the person's, so it is only known not to be a stop)
    assert {e.reason for e in s.log.of(UtteranceIgnored)} <= {"own_voice", "no_wake_word", "not_a_stop"}
    assert not s.log.of(StopHeard)


async def test_referenced_sink_places_playback_where_it_will_sound() -> None:
    from robovoice.audio.wav import MemorySink
    from robovoice.voice.echo import PlaybackReference
    from robovoice.voice.playback import ReferencedSink

    now = [100.0]
    reference = PlaybackReference()
    sink = ReferencedSink(MemorySink(), reference, output_latency_s=0.05, clock=lambda: now[0])
    half = tone(0.5)
    await sink.write(half)
    await sink.write(half)  # queued behind the first
    assert reference.end_time == pytest.approx(101.05)
    assert reference.playing(100.06, 100.1) and not reference.playing(100.0, 100.04)
    now[0] = 100.3
    sink.stop()  # barge-in: nothing more sounds after now
    assert not reference.playing(100.31, 101.1) and reference.playing(100.1, 100.29)


async def test_the_speculative_transcript_is_used_one_stt_run_per_command(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(TextReply("It is on."), TextReply("It is off."))
    async with voice_session(fakes, backend, speed=2.0) as s:
        stt = s.pipeline.stt
        assert stt is not None
        for n, said in enumerate(("Hey Jarvis, turn on the projector.", "Hey Jarvis, turn it off."), start=1):
            transcriber.text = said
            await s.say(wake_command(), gap_s=0.8)
            await s.log.wait_for(VoiceTurnFinished, lambda e, n=n: e.turn == n)  # type: ignore[misc]  # n bound per turn
            await s.settle()
            # started at the pause (inside the end-of-turn silence), and that run was the one used
            assert (transcriber.calls, stt.speculated, stt.reused) == (n, n, n)
    assert [e.text for e in s.log.of(TranscriptReady)] == ["turn on the projector.", "turn it off."]


async def test_a_speculative_transcript_is_dropped_when_the_utterance_goes_on(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(TextReply("Done."))
    # what speech-to-text hears depends on how much of the utterance it gets
    transcriber.by_length = lambda seconds: ("Hey Jarvis, turn on the projector and the light." if seconds > 2.4
                                             else "Hey Jarvis, turn on the")
    said = join(tone(0.5), babble(1.0), silence(MODEL_FORMAT, 0.3), babble(1.0, seed=3))
    async with voice_session(fakes, backend, speed=2.0) as s:
        await s.say(said)  # a pause too short to end the turn, then more words
        started = await s.log.wait_for(VoiceTurnStarted)
        await s.settle()
    stt = s.pipeline.stt
    assert stt is not None and stt.speculated == 2 and stt.reused == 1
    assert started.text == "turn on the projector and the light."
    said_to_model = [m["content"] for m in server.requests[0].messages if m["role"] == "user"]
    assert said_to_model[0] == "turn on the projector and the light."  # (then: one thing at a time)
    assert transcriber.durations[-1] > 2.4, "the transcript used covers the whole utterance"


async def test_the_demo_takes_wake_phrase_and_vocabulary_from_the_config(
    transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend, tmp_path: Path
) -> None:
    from robovoice.assistant.connect import connect_robot
    from robovoice.audio.fakes import ToneSynthesizer
    from robovoice.config import RobotConfig
    from robovoice.voice.demo import Step, run_demo

    server.push(TextReply("Hello."))
    transcriber.text = "Hello robot, what is that shed called?"
    config = VoiceConfig(wake_phrase="hello robot", vocabulary=("garden shed", "Grandma Ruth"))
    async with connect_robot(RobotConfig(address="sim://?speed=10")) as robot:
        assert robot.sim is not None
        report = await run_demo(fake_models(transcriber), backend, robot.tools, robot.sim, output_dir=tmp_path,
                                user_voice=ToneSynthesizer(seconds_per_char=0.02, frequency=1000.0),
                                steps=[Step("a question", say="x" * 40)], config=config, step_timeout_s=30.0)
    assert report.ok
    assert transcriber.hints and transcriber.hints[-1].startswith("Hello Robot. ")
    assert "garden shed, Grandma Ruth" in transcriber.hints[-1]
    assert server.requests[0].last_user_text == "what is that shed called?", "its wake phrase was stripped"
