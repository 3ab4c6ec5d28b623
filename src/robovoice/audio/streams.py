"""The two I/O seams of the voice pipeline: where audio comes from and where it goes.

Real implementations: `devices.MicrophoneSource` / `devices.SpeakerSink` (sounddevice);
first-class fakes: `wav.WavSource`, `wav.WavSink`, `wav.MemorySink`.
"""

from __future__ import annotations

from collections.abc import AsyncIterator
from typing import Protocol, runtime_checkable

from robovoice.audio.format import AudioChunk, AudioFormat, FormatConverter


@runtime_checkable
class AudioSource(Protocol):
    """An async stream of chunks in one `format`, ended by the source or by `aclose()`."""

    @property
    def format(self) -> AudioFormat: ...

    def __aiter__(self) -> AsyncIterator[AudioChunk]: ...

    async def aclose(self) -> None:
        """Stop producing; a running iteration ends after the current chunk."""
        ...


@runtime_checkable
class AudioSink(Protocol):
    """Plays (or stores) audio written to it.

    `write` may return before the audio is heard (it is queued); `drain` waits until all
    queued audio has been played; `stop` is the barge-in control: it drops everything
    still queued at once and returns immediately.
    """

    async def write(self, chunk: AudioChunk) -> None: ...

    async def drain(self) -> None: ...

    def stop(self) -> None: ...

    async def aclose(self) -> None: ...


async def converted(source: AsyncIterator[AudioChunk], fmt: AudioFormat) -> AsyncIterator[AudioChunk]:
    """Re-yield a chunk stream in `fmt` (e.g. any WAV or microphone -> 16 kHz mono int16)."""
    converter = FormatConverter(fmt)
    async for chunk in source:
        out = converter.convert(chunk)
        if out.num_frames:
            yield out
    tail = converter.flush()
    if tail is not None:
        yield tail
