"""Using the end-of-turn silence (docs/voice.md): what the speculative transcript taken at a
pause is used for before the end of turn is decided.

1. **A shorter silence.** When its words form a complete request (`completeness.is_complete`),
   the pause may end the utterance after `early_silence_s` (``[voice] early_end_silence_ms``)
   instead of the full end-of-turn silence (`HeardPause.end_early`; the endpointer voids it if speech resumes).
   Never for a stop phrase: what may follow it is part of the command.
2. **Speculative prefill.** For an addressed command, the assistant's first model step for those
   words (`Assistant.first_request`) is handed to a backend that can prefill
   (`LocalLlamaBackend.prefill`: the prompt goes into the model's cache, the tool call is
   decoded); the real turn reuses that work only if its transcript is the same. Nothing is
   sent to the robot from here: only a real turn's stream yields the call, and only the
   assistant runs it.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

from robovoice.assistant.loop import Assistant
from robovoice.llm.base import ChatMessage, ToolSpec
from robovoice.voice.completeness import is_complete
from robovoice.voice.config import SpeculationConfig as SpeculationConfig  # the router imports it from here
from robovoice.voice.listener import HeardPause
from robovoice.voice.stop import is_stop_command
from robovoice.voice.utterance import Transcription, strip_wake_words

log = logging.getLogger(__name__)


@runtime_checkable
class Prefilling(Protocol):
    """A backend that can evaluate a turn's prompt ahead of the turn."""

    async def prefill(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec], *, decode: bool = True
    ) -> object: ...


@dataclass(slots=True)
class SpeculationStats:
    transcripts: int = 0  # speculative transcripts that arrived
    early_ends: int = 0  # ... that allowed the shorter silence
    prefills: int = 0  # prefills started


class Speculator:
    """Follows each speculative transcription (see the module docstring)."""

    def __init__(self, config: SpeculationConfig, assistant: Assistant, wake_phrase: str) -> None:
        self.config = config
        self.assistant = assistant
        self.wake_phrase = wake_phrase
        self.stats = SpeculationStats()

    async def follow(self, pause: HeardPause, transcription: Transcription, *, woken: bool, command: bool) -> None:
        """When `transcription` (of the utterance up to `pause`) is ready: the early end if its
        words are complete, and a prefill for a `command` (an addressed one, for a text model).
        `woken`: the wake phrase may start the transcript (it is removed first)."""
        await asyncio.wait([transcription])  # its cancellation (speech went on) is not ours
        if transcription.cancelled() or transcription.exception() is not None:
            return
        raw = transcription.result()[0].text
        text = strip_wake_words(raw, self.wake_phrase) if woken else raw.strip()
        self.stats.transcripts += 1
        # not after a stop: what may follow it ("stop there, and then go back to your charger")
        # is part of the command; the stop itself acts at this pause (`StopController.check_pause`)
        stop = is_stop_command(text)
        if self.config.early_end and is_complete(text) and not stop:
            pause.end_early(self.config.early_silence_s)
            self.stats.early_ends += 1
        if command and self.config.prefill and text and not stop:
            await self._prefill(text)

    async def _prefill(self, text: str) -> None:
        backend = self.assistant.backend
        if not isinstance(backend, Prefilling):
            return
        self.stats.prefills += 1
        try:
            messages, tools = await self.assistant.first_request(text)
            await backend.prefill(messages, tools, decode=self.config.decode)
        except asyncio.CancelledError:
            raise
        except Exception as exc:  # a guess that failed (the robot's tool list, the model) costs the turn nothing
            log.warning("speculative prefill for %r failed: %s", text, exc)
