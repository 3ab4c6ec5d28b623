"""Text for the terminal: shared helpers for the commands' live output."""

from __future__ import annotations

import logging

from robovoice.assistant.speech_guard import unspeakable_in, without_end_marker

log = logging.getLogger(__name__)


def one_line(text: str, limit: int = 110) -> str:
    """`text` on one line (each run of whitespace becomes one space), cut to `limit`
    characters with a trailing "…" when longer."""
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 1] + "…"


def shown_reply(sentence: str) -> str | None:
    """An assistant sentence as the terminal shows it, or None (logged) when it carries tool-call
    syntax: raw ``functions.x:`` or ``<tool_call>`` text is never printed as the robot's words."""
    sentence = without_end_marker(sentence)
    if (unspeakable := unspeakable_in(sentence)) is not None:
        log.warning("not showing a sentence with the model's instructions or tool-call syntax %r: %r",
                    unspeakable, sentence[:200])
        return None
    return sentence if sentence.strip() else None
