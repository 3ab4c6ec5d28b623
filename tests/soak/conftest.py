"""Fixtures for the soak tests: the shipped voice models, loaded once, and a fake model server
routing by keywords."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterator

import pytest

from robovoice.llm.fake_server import CallbackReply, FakeOpenAIServer
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.models import VoiceModels

from ..voice.voice_kit import keyword_router


@pytest.fixture(scope="session")
def voice_models() -> Iterator[VoiceModels]:
    from robovoice.voice.models import load_voice_models

    yield load_voice_models()


@pytest.fixture
async def backend() -> AsyncIterator[OpenAICompatBackend]:
    async with FakeOpenAIServer() as server:
        server.default = CallbackReply(keyword_router)
        b = OpenAICompatBackend(server.base_url, server.model)
        yield b
        await b.aclose()
