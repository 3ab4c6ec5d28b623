"""Text for the terminal: one shared helper for the commands' live output."""

from __future__ import annotations


def one_line(text: str, limit: int = 110) -> str:
    """`text` on one line (each run of whitespace becomes one space), cut to `limit`
    characters with a trailing "…" when longer."""
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 1] + "…"
