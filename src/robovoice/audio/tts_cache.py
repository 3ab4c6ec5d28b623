"""Fixed phrases synthesised once: a small cache in front of a `Synthesizer`.

The robot says some sentences again and again ("Stopped.", "Sorry, I didn't catch that.",
"On my way to the kitchen.", a tool's success phrase, the fallback message). Piper takes
about 0.1-0.3 s of CPU for each on 2 cores; said again from the cache it costs nothing, and
the first audio of such a reply comes that much sooner. `CachedSynthesizer` keeps the audio of
short sentences (at most `max_chars`), keyed by the voice and the exact text, the most
recently said `max_entries` of them; longer text (the model's own wording, rarely said twice)
always goes to the synthesiser. `warm(texts)` synthesises known phrases ahead of their
first use. Cached chunks are shared: `AudioChunk` samples are read-only.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Iterable, Iterator

import numpy as np

from robovoice.audio.format import AudioChunk, AudioFormat, concat
from robovoice.audio.tts import PiperSynthesizer, Synthesizer


def voice_of(synth: Synthesizer) -> str:
    """What makes one synthesiser's audio differ from another's for the same text."""
    if isinstance(synth, PiperSynthesizer):
        return synth.voice_id
    return f"{type(synth).__name__}@{id(synth):x}"


class CachedSynthesizer:
    """A `Synthesizer` that says short sentences it has said before from memory. Safe to call
    from several threads (the speech executor), like the synthesiser it wraps."""

    def __init__(self, inner: Synthesizer, *, max_entries: int = 64, max_chars: int = 80) -> None:
        if max_entries < 1 or max_chars < 1:
            raise ValueError(f"max_entries and max_chars must be at least 1, got {max_entries} and {max_chars}")
        self.inner = inner
        self.voice = voice_of(inner)
        self.max_entries = max_entries
        self.max_chars = max_chars
        self._audio: OrderedDict[tuple[str, str], tuple[AudioChunk, ...]] = OrderedDict()
        self._lock = threading.Lock()
        self.hits = 0
        self.misses = 0

    @property
    def format(self) -> AudioFormat:
        return self.inner.format

    def warm(self, texts: Iterable[str]) -> None:
        """Synthesise these phrases now (at start-up), so their first use is served from memory."""
        for text in texts:
            self._chunks(text)

    def synthesize(self, text: str) -> AudioChunk:
        chunks = self._chunks(text)
        if chunks is None:
            return self.inner.synthesize(text)
        if not chunks:
            return AudioChunk(np.zeros(0, dtype=self.format.dtype), self.format)
        return chunks[0] if len(chunks) == 1 else concat(list(chunks))

    def synthesize_stream(self, text: str) -> Iterator[AudioChunk]:
        chunks = self._chunks(text)
        if chunks is None:
            yield from self.inner.synthesize_stream(text)
        else:
            yield from chunks

    def _chunks(self, text: str) -> tuple[AudioChunk, ...] | None:
        """The phrase's audio, synthesised on first use; None for text too long to keep."""
        if len(text) > self.max_chars:
            return None
        key = (self.voice, text)
        with self._lock:
            found = self._audio.get(key)
            if found is not None:
                self._audio.move_to_end(key)
                self.hits += 1
                return found
        # synthesised outside the lock: another sentence may be synthesised meanwhile
        chunks = tuple(self.inner.synthesize_stream(text))
        with self._lock:
            self.misses += 1
            self._audio[key] = chunks
            while len(self._audio) > self.max_entries:
                self._audio.popitem(last=False)
        return chunks
