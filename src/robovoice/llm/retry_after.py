"""HTTP 429/503 with ``Retry-After``: a busy server that says when to come back.

`OpenAICompatBackend` waits and retries once when the wait fits in what is left of the
first-token deadline (the user is waiting anyway); otherwise it raises `RetryAfterError`, an
`LLMHTTPError` that carries the wait, so that a failover chain moves on to the next backend
at once instead of idling on this one.
"""

from __future__ import annotations

import datetime
import email.utils
import math
import time

from robovoice.llm.base import LLMHTTPError

RETRYABLE_STATUS = frozenset({429, 503})


class RetryAfterError(LLMHTTPError):
    """The server is busy (429/503) and asked to retry after ``retry_after`` seconds."""

    def __init__(self, status_code: int, server_message: str, url: str, retry_after: float) -> None:
        super().__init__(status_code, server_message, url)
        self.retry_after = retry_after
        self.args = (f"{self.args[0]} (the server asks to retry after {retry_after:g} s)",)


def retry_after_seconds(value: str | None, now: float | None = None) -> float | None:
    """Seconds to wait from a ``Retry-After`` value: delta-seconds ("3", "0.5") or an HTTP-date
    (RFC 9110 §10.2.3). None when absent or unreadable; a date in the past is 0."""
    if value is None or not value.strip():
        return None
    text = value.strip()
    try:
        seconds = float(text)
    except ValueError:
        try:
            when = email.utils.parsedate_to_datetime(text)
        except (TypeError, ValueError):
            return None
        if when.tzinfo is None:  # an HTTP-date is always GMT; a zone-less one is read as such
            when = when.replace(tzinfo=datetime.UTC)
        seconds = when.timestamp() - (time.time() if now is None else now)
    if not math.isfinite(seconds):
        return None
    return max(0.0, seconds)
