"""Fixtures for the soak tests: the shipped voice models, loaded once."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from robovoice.voice.models import VoiceModels


@pytest.fixture(scope="session")
def voice_models() -> Iterator[VoiceModels]:
    from robovoice.voice.models import load_voice_models

    yield load_voice_models()
