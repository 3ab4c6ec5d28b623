""""One moment.": said once when the model keeps the user waiting in silence, never when it
answers quickly, and not at all when switched off. The voice pipeline with model fakes and the
fake vLLM server, whose first token is held back as a CPU server's prefill would."""

from __future__ import annotations

import pytest

from robovoice.config import VoiceConfig
from robovoice.llm.fake_server import FakeOpenAIServer, Pacing, ScriptedCall, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.events import SentenceSpoken, VoiceTurnFinished
from robovoice.voice.models import VoiceModels

from .voice_kit import SettableTranscriber, voice_session, wake_command

pytestmark = pytest.mark.timeout(90)

SLOW = Pacing(first_token_delay_s=3.0)  # the model reads its prompt for 3 s


async def _spoken(fakes: VoiceModels, backend: OpenAICompatBackend, config: VoiceConfig | None = None,
                  turns: int = 1) -> tuple[list[tuple[str, str]], list[VoiceTurnFinished]]:
    async with voice_session(fakes, backend, speed=2.0, config=config) as s:
        for _ in range(turns):
            await s.say(wake_command())
            await s.log.wait_for(VoiceTurnFinished, after=len(s.log.events))
            await s.settle()
    return [(e.text, e.kind) for e in s.log.of(SentenceSpoken)], s.log.of(VoiceTurnFinished)


async def test_a_slow_model_gets_one_moment_once_before_its_answer(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(TextReply("The battery is at eighty percent. It is not charging.", pacing=SLOW))
    transcriber.text = "Hey Jarvis, how much battery do you have?"
    spoken, finished = await _spoken(fakes, backend)
    assert spoken == [("One moment.", "wait"), ("The battery is at eighty percent.", "reply"),
                      ("It is not charging.", "reply")]
    marks = finished[0].latency_ms
    assert marks["one_moment"] < marks["first_sentence"] <= marks["first_audio"]  # first_audio is the answer's


async def test_a_fast_model_gets_none(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(TextReply("The battery is at eighty percent."))
    transcriber.text = "Hey Jarvis, how much battery do you have?"
    spoken, finished = await _spoken(fakes, backend)
    assert spoken == [("The battery is at eighty percent.", "reply")]
    assert "one_moment" not in finished[0].latency_ms


async def test_each_slow_step_of_a_turn_shares_one_one_moment_and_each_turn_has_its_own(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    """A slow call and a slow answer after it: one "One moment." in the turn; the next slow turn
    gets its own."""
    # a read-only tool: the model words its result (an action's phrase would answer without it)
    server.push(ToolCallReply((ScriptedCall("get_battery_state", {}),), pacing=SLOW),
                TextReply("The battery is fine.", pacing=SLOW), TextReply("It is still fine.", pacing=SLOW))
    transcriber.text = "Hey Jarvis, how much battery do you have?"
    spoken, _ = await _spoken(fakes, backend, turns=2)
    texts = [text for text, _ in spoken]
    assert texts.count("One moment.") == 2, spoken
    assert texts.index("One moment.") < texts.index("The battery is fine.") < texts.index("It is still fine.")


async def test_switched_off_it_is_never_said(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(TextReply("The battery is at eighty percent.", pacing=SLOW))
    transcriber.text = "Hey Jarvis, how much battery do you have?"
    spoken, _ = await _spoken(fakes, backend, VoiceConfig(one_moment=""))
    assert spoken == [("The battery is at eighty percent.", "reply")]


async def test_the_phrase_and_the_wait_come_from_the_config(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    server.push(TextReply("Eighty percent.", pacing=Pacing(first_token_delay_s=1.5)))
    transcriber.text = "Hey Jarvis, how much battery do you have?"
    config = VoiceConfig(one_moment="Let me think.", one_moment_after_s=0.3)
    spoken, _ = await _spoken(fakes, backend, config)
    assert spoken == [("Let me think.", "wait"), ("Eighty percent.", "reply")]
