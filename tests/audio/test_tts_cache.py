"""Fixed phrases synthesised once: the cache in front of the real Piper voice."""

from __future__ import annotations

import time
from collections.abc import Iterator

import numpy as np
import pytest

from robovoice.audio.format import AudioChunk, AudioFormat
from robovoice.audio.tts import PiperSynthesizer
from robovoice.audio.tts_cache import CachedSynthesizer, voice_of
from robovoice.llm.failover import FALLBACK_MESSAGE


class Counted:
    """The real synthesiser, counting what it is asked to say."""

    def __init__(self, inner: PiperSynthesizer) -> None:
        self.inner = inner
        self.texts: list[str] = []

    @property
    def format(self) -> AudioFormat:
        return self.inner.format

    def synthesize(self, text: str) -> AudioChunk:
        self.texts.append(text)
        return self.inner.synthesize(text)

    def synthesize_stream(self, text: str) -> Iterator[AudioChunk]:
        self.texts.append(text)
        return self.inner.synthesize_stream(text)


def test_a_phrase_said_again_does_not_reach_the_synthesiser(piper: PiperSynthesizer) -> None:
    counted = Counted(piper)
    cache = CachedSynthesizer(counted)
    t0 = time.perf_counter()
    first = cache.synthesize("Stopped.")
    synthesised_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    again = cache.synthesize("Stopped.")
    cached_s = time.perf_counter() - t0
    streamed = list(cache.synthesize_stream("Stopped."))
    assert counted.texts == ["Stopped."]  # once, for three requests
    assert cache.hits == 2 and cache.misses == 1
    assert first.duration_s > 0.3 and np.array_equal(first.samples, again.samples)
    assert np.array_equal(np.concatenate([c.samples for c in streamed]), first.samples)
    assert cached_s < synthesised_s / 10
    # other text is synthesised
    cache.synthesize("Sorry, I didn't catch that.")
    assert counted.texts == ["Stopped.", "Sorry, I didn't catch that."]


def test_warm_synthesises_ahead_and_long_text_is_never_kept(piper: PiperSynthesizer) -> None:
    counted = Counted(piper)
    cache = CachedSynthesizer(counted, max_chars=len(FALLBACK_MESSAGE), max_entries=2)
    cache.warm(["Stopped.", FALLBACK_MESSAGE])
    assert counted.texts == ["Stopped.", FALLBACK_MESSAGE]
    cache.synthesize(FALLBACK_MESSAGE)
    cache.synthesize("Stopped.")
    assert len(counted.texts) == 2
    long = "I have looked everywhere in the living room and I could not find your glasses anywhere, sorry."
    cache.synthesize(long)
    cache.synthesize(long)
    assert counted.texts[2:] == [long, long]
    cache.synthesize("On my way to the kitchen.")  # a third phrase: the least recently said one goes
    cache.synthesize(FALLBACK_MESSAGE)
    assert counted.texts[4:] == ["On my way to the kitchen.", FALLBACK_MESSAGE]


def test_the_key_names_the_voice_and_bad_sizes_are_refused(piper: PiperSynthesizer) -> None:
    assert voice_of(piper) == f"piper:{piper.model_path.name}:None:None:0.9:0.15"
    assert CachedSynthesizer(piper).voice == voice_of(piper) != voice_of(Counted(piper))
    with pytest.raises(ValueError, match="max_entries and max_chars must be at least 1, got 0 and 80"):
        CachedSynthesizer(piper, max_entries=0)
