"""No tool-call syntax is ever spoken or printed: the guard itself, the terminal's filter, and
the real voice pipeline (model fakes, the sim robot over MCP) with backends that leak it."""

from __future__ import annotations

import json
import logging
from collections.abc import AsyncGenerator, Sequence
from dataclasses import replace

import pytest

from robovoice.assistant.speech_guard import speakable, tool_syntax_in
from robovoice.audio.fakes import ToneSynthesizer
from robovoice.commands.text import shown_reply
from robovoice.llm.base import ChatMessage, Finished, LLMEvent, TextDelta, ToolSpec
from robovoice.llm.fake_server import (
    CallbackReply,
    FakeOpenAIServer,
    Quirks,
    ScriptedCall,
    ScriptedReply,
    ToolCallReply,
)
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.events import SentenceSpoken, VoiceTurnFinished
from robovoice.voice.models import VoiceModels

from .voice_kit import SettableTranscriber, voice_session, wake_command

pytestmark = pytest.mark.timeout(90)

LEAKS = [
    "functions.get_battery_state:",
    'functions.navigate_to:\n{"target": "kitchen"}',
    "Sure! functions.navigate_to",
    '<tool_call>\n{"name": "navigate_to", "arguments": {"target": "kitchen"}}\n</tool_call>',
    "</tool_call>",
    '{"name": "navigate_to", "arguments": {"target": "kitchen"}}',
    '{"arguments": {"target": "kitchen"}, "name": "navigate_to"}',
    '[TOOL_CALLS][{"name": "navigate_to", "arguments": {}}]',
    "<|im_start|>assistant",
    "<|im_end|> All done.",
    "<|python_tag|>navigate_to(target='kitchen')",
    "<function=navigate_to>{\"target\": \"kitchen\"}</function>",
    "<tool_response>ok</tool_response>",
    "<think>\nThe user wants the kitchen.",
    "I should call navigate_to.</think>",
    "The robot did not ask for set_projector_power.",  # a tool's name read out from an error message
]

SPEAKABLE = [
    "I have several functions.",
    "My functions. Well, I can drive and talk.",
    "The kitchen is to the left.",
    "Three is < four, and {braces} are fine.",
    "My name is Robo, and my arguments are good ones.",
    "I use a function call to drive.",
    "It's a well-known, up-to-date place.",
]


@pytest.mark.parametrize("sentence", LEAKS)
def test_tool_call_syntax_is_never_speakable(sentence: str) -> None:
    assert speakable(sentence) is None
    assert tool_syntax_in(sentence)
    assert shown_reply(sentence) is None


@pytest.mark.parametrize("sentence", SPEAKABLE)
def test_ordinary_sentences_pass_unchanged(sentence: str) -> None:
    assert speakable(sentence) == sentence and tool_syntax_in(sentence) is None
    assert shown_reply(sentence) == sentence


@pytest.mark.parametrize("sentence", ["All done.<|im_end|>", "All done. <|eot_id|>", "All done.<end_of_turn>\n"])
def test_an_end_of_turn_marker_at_the_end_is_cut_off_not_the_sentence(sentence: str) -> None:
    assert speakable(sentence) == "All done." and shown_reply(sentence) == "All done."
    assert speakable("<|im_end|>") is None and shown_reply("<|im_end|>") is None


def test_the_terminal_filter_logs_what_it_drops(caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING, logger="robovoice.commands.text"):
        assert shown_reply("functions.get_battery_state:") is None
    assert "tool-call syntax 'functions.get_battery_state'" in caplog.text


class LeakyBackend:
    """A model that writes its tool-call syntax as words, in forms no backend turns into a call
    (what reached the user in issue 16), then one real sentence. (A sentence that carries a
    control token is dropped whole, unless it is the end-of-turn marker at its end.)"""

    name = "leaky"
    accepts_audio = False

    def __init__(self) -> None:
        self.turns = 0

    async def stream(self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]
                     ) -> AsyncGenerator[LLMEvent, None]:
        self.turns += 1
        for piece in ("<|im_start|>assistant\n", "functions.get_battery_state:\n", "<tool_call>\n",
                      '{"name": "get_battery_state", ', '"arguments": {}}\n', "</tool_call>\n",
                      "I am fine, thank you."):
            yield TextDelta(piece)
        yield Finished("stop")

    async def aclose(self) -> None:
        pass


def recording_models(fakes: VoiceModels) -> tuple[VoiceModels, ToneSynthesizer]:
    tts = ToneSynthesizer(seconds_per_char=0.02)
    return replace(fakes, tts=tts), tts


def assert_clean(texts: Sequence[str]) -> None:
    leaked = [t for t in texts if tool_syntax_in(t) or "functions." in t or "tool_call" in t]
    assert not leaked, leaked


async def test_the_voice_pipeline_never_speaks_leaked_syntax(
    fakes: VoiceModels, transcriber: SettableTranscriber, caplog: pytest.LogCaptureFixture
) -> None:
    models, tts = recording_models(fakes)
    backend = LeakyBackend()
    transcriber.text = "Hey Jarvis, how are you?"
    with caplog.at_level(logging.WARNING, logger="robovoice"):
        async with voice_session(models, backend, speed=2.0) as s:
            await s.say(wake_command())
            await s.log.wait_for(VoiceTurnFinished)
            await s.settle()
    assert backend.turns == 1
    spoken = [e.text for e in s.log.of(SentenceSpoken)]
    assert "I am fine, thank you." in spoken and "I am fine, thank you." in tts.texts
    assert_clean(spoken)
    assert_clean(tts.texts)  # nothing with the syntax was even synthesised
    assert "tool-call syntax or the model's instructions" in caplog.text  # held back by the loop itself


async def test_the_voice_pipeline_acts_on_calls_a_server_wrote_as_text(
    fakes: VoiceModels, transcriber: SettableTranscriber
) -> None:
    """Through the real HTTP wire: a Qwen/Hermes-style server with no finish reason."""
    models, tts = recording_models(fakes)
    switch_on = ScriptedCall("set_projector_power", {"on": True})
    script: list[ScriptedReply] = [ToolCallReply((switch_on,), text="Switching it on.")]
    async with FakeOpenAIServer(script, quirks=Quirks(tool_calls_as="hermes", no_finish_reason=True)) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        transcriber.text = "Hey Jarvis, turn on the projector."
        try:
            async with voice_session(models, backend, speed=2.0) as s:
                await s.say(wake_command())
                done = await s.log.wait_for(VoiceTurnFinished)
                await s.settle()
                assert s.sim.state.projector_on
        finally:
            await backend.aclose()
    assert done.result is not None and [c.name for c in done.result.calls] == ["set_projector_power"]
    spoken = [e.text for e in s.log.of(SentenceSpoken)]
    assert spoken[-1] == "The projector is now on."  # its success phrase: no second model step
    assert_clean(spoken)
    assert_clean(tts.texts)


async def test_the_voice_pipeline_never_speaks_the_gate_hint_the_model_reads_out(
    fakes: VoiceModels, transcriber: SettableTranscriber, caplog: pytest.LogCaptureFixture
) -> None:
    """Issue 11: the model reads the refusal's hint out before its own answer."""
    from ..assistant.test_model_only_text import echo_the_hint

    models, tts = recording_models(fakes)
    transcriber.text = "Hey Jarvis, did you go to the bathroom today?"  # a question: the model words the answer
    with caplog.at_level(logging.WARNING, logger="robovoice.voice.speech"):
        async with FakeOpenAIServer(default=CallbackReply(echo_the_hint)) as server:
            backend = OpenAICompatBackend(server.base_url, server.model)
            try:
                async with voice_session(models, backend, speed=2.0) as s:
                    await s.say(wake_command())
                    await s.log.wait_for(VoiceTurnFinished)
                    await s.settle()
                    assert not s.sim.state.moving
            finally:
                await backend.aclose()
    hint = json.loads(server.requests[1].messages[-1]["content"])["hint"]
    spoken = [e.text for e in s.log.of(SentenceSpoken)]
    assert spoken == ["Not today."] and tts.texts == spoken
    assert "the model's instructions" in caplog.text and hint.split(".")[0] in caplog.text
