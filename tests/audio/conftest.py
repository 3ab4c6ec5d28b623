"""Shared fixtures for the audio tests: the real models, loaded once per session."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest


@pytest.fixture(scope="session")
def wake_detector() -> Iterator[Any]:
    from robovoice.audio.wake import OpenWakeWordDetector

    yield OpenWakeWordDetector()


@pytest.fixture(scope="session")
def silero() -> Iterator[Any]:
    from robovoice.audio.vad import SileroVAD

    yield SileroVAD()


@pytest.fixture(scope="session")
def moonshine() -> Iterator[Any]:
    from robovoice.audio.stt import MoonshineTranscriber

    yield MoonshineTranscriber()


@pytest.fixture(scope="session")
def piper() -> Iterator[Any]:
    from robovoice.audio.tts import PiperSynthesizer

    yield PiperSynthesizer()


@pytest.fixture(scope="session")
def whisper() -> Iterator[Any]:
    from robovoice.audio.stt import WhisperTranscriber

    yield WhisperTranscriber()
