"""Waiting in tests for something that happens on the event loop, bounded (no fixed sleeps)."""

from __future__ import annotations

import asyncio
from collections.abc import Callable

import pytest

#: The longest a test waits for a condition by default (real seconds, on a busy 2-core machine).
BOUND_S = 10.0


async def until(condition: Callable[[], bool], bound: float = BOUND_S, what: str = "the condition",
                poll_s: float = 0.005) -> None:
    """Poll `condition()` on the event loop until it holds; fail the test, naming `what`, after
    `bound` seconds."""
    try:
        async with asyncio.timeout(bound):
            while not condition():
                await asyncio.sleep(poll_s)
    except TimeoutError:
        pytest.fail(f"{what} did not hold within {bound:g} s")
