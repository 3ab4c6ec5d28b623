"""Fixtures for the voice tests: the real voice models (loaded once), fake models, a fake
LLM server speaking vLLM's wire format."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterator

import pytest

from robovoice.llm.fake_server import FakeOpenAIServer
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.models import VoiceModels

from .voice_kit import SettableTranscriber, fake_models


@pytest.fixture(scope="session")
def voice_models() -> Iterator[VoiceModels]:
    """openWakeWord (x2), Silero VAD, Moonshine, Piper: loaded once for the session."""
    from robovoice.voice.models import load_voice_models

    yield load_voice_models()


@pytest.fixture
def transcriber() -> SettableTranscriber:
    return SettableTranscriber()


@pytest.fixture
def fakes(transcriber: SettableTranscriber) -> VoiceModels:
    return fake_models(transcriber)


@pytest.fixture
async def server() -> AsyncIterator[FakeOpenAIServer]:
    async with FakeOpenAIServer() as srv:
        yield srv


@pytest.fixture
async def backend(server: FakeOpenAIServer) -> AsyncIterator[OpenAICompatBackend]:
    b = OpenAICompatBackend(server.base_url, server.model)
    yield b
    await b.aclose()
