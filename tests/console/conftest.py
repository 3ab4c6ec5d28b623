"""Fixtures for the console tests: the real voice models, loaded once for the session."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from robovoice.voice.models import VoiceModels


@pytest.fixture(scope="session")
def voice_models() -> Iterator[VoiceModels]:
    """openWakeWord (x2), Silero VAD, Whisper, Piper: loaded once (5-15 s on 2 cores)."""
    from robovoice.voice.models import load_voice_models

    yield load_voice_models()
