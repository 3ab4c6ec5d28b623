"""Spoken confirmation through the voice pipeline (issue 11): a command transcript in doubt
(`voice.confidence.doubtful`) does not start a video call; the robot asks, and the answer,
said without the wake word in the follow-up window, is read locally."""

from __future__ import annotations

import pytest

from robovoice.audio.stt import Confidence, Transcript
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedCall, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.confidence import doubtful
from robovoice.voice.config import ConfidenceCheck, PipelineConfig
from robovoice.voice.events import SentenceSpoken, VoiceTurnFinished

from .test_confidence import SURE, ScoredTranscriber
from .voice_kit import babble, fake_models, voice_session, wake_command

pytestmark = pytest.mark.timeout(90)

IN_DOUBT = -0.5  # above the turn-away threshold (-0.6), below the confirm one (-0.4)


def test_doubt_lies_between_the_two_thresholds() -> None:
    check = PipelineConfig.from_config().confidence
    assert check.confirm_below == -0.4  # chosen on the dev audio (docs/judgement.md)
    assert check.min_avg_logprob is not None and check.min_avg_logprob < IN_DOUBT < check.confirm_below < SURE

    def heard(logprob: float) -> Transcript:
        return Transcript("Call Anna.", 1.0, confidence=Confidence((), logprob, 0.01))

    assert doubtful(heard(IN_DOUBT), check) and not doubtful(heard(SURE), check)
    assert not doubtful(heard(IN_DOUBT), ConfidenceCheck(-0.6, None))  # confirm_doubtful = false
    assert not doubtful(Transcript("Call Anna.", 1.0), check)  # no scores (Moonshine): never in doubt


@pytest.mark.parametrize(("answer", "calls"), [("Yes, please.", True), ("No.", False)])
async def test_a_call_heard_in_doubt_waits_for_a_spoken_yes(
    answer: str, calls: bool, server: FakeOpenAIServer, backend: OpenAICompatBackend,
) -> None:
    stt = ScoredTranscriber()
    server.push(ToolCallReply((ScriptedCall("start_video_call", {"contact": "Anna"}),)))
    async with voice_session(fake_models(stt), backend, speed=2.0) as s:
        stt.text, stt.avg_logprob = "Hey Jarvis, call Anna.", IN_DOUBT
        await s.say(wake_command())
        asked = await s.log.wait_for(VoiceTurnFinished)
        await s.settle()
        assert s.sim.state.call_contact is None  # nothing reached the robot yet
        stt.text, stt.avg_logprob = answer, SURE
        await s.say(babble(0.8), gap_s=0.8)  # no wake word: it answers the question
        answered = await s.log.wait_for(VoiceTurnFinished, lambda e: e is not asked, timeout=60)
        await s.settle()
    assert asked.result is not None and asked.result.reply == "Shall I call Anna?"
    assert len(server.requests) == 1  # the answer was read without the model
    assert answered.result is not None
    assert [c.name for c in answered.result.calls] == (["start_video_call"] if calls else [])
    assert s.sim.state.call_contact == ("Anna" if calls else None)
    spoken = [e.text for e in s.log.of(SentenceSpoken)]
    assert spoken[-1] == ("I am in a video call with Anna now." if calls else "All right, I won't.")
