"""Simulated time: the sim's one clock, optionally faster than real time.

Every part of the simulated robot reads time from a `SimClock` and sleeps on it, so a
test or a demo can run the whole robot at, say, 20x: a 20 s drive then takes 1 s of
wall-clock time, and a topic published at 10 Hz sim time arrives at 200 Hz real time.
Sim time starts at 0 when the clock is created and is measured in seconds.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import AsyncIterator

log = logging.getLogger(__name__)


class SimClock:
    """Sim seconds since creation, running `speed` times faster than the monotonic clock."""

    def __init__(self, speed: float = 1.0) -> None:
        if not speed > 0:
            raise ValueError(f"sim speed must be positive, got {speed!r}")
        self._speed = float(speed)
        self._origin = time.monotonic()

    @property
    def speed(self) -> float:
        """How many sim seconds pass per real second."""
        return self._speed

    def now(self) -> float:
        """Sim seconds since the clock was created."""
        return (time.monotonic() - self._origin) * self._speed

    def to_real(self, sim_seconds: float) -> float:
        """The real (wall-clock) duration of `sim_seconds`."""
        return sim_seconds / self._speed

    async def sleep(self, sim_seconds: float) -> None:
        """Sleep for `sim_seconds` of sim time (at least one loop iteration)."""
        await asyncio.sleep(max(0.0, sim_seconds) / self._speed)

    async def sleep_until(self, sim_time: float) -> None:
        """Sleep until the sim clock reads `sim_time` (returns at once if it is past)."""
        await self.sleep(sim_time - self.now())

    async def ticks(self, period: float) -> AsyncIterator[float]:
        """Yield the sim time once per `period` sim seconds, on a fixed schedule.

        Ticks are scheduled on absolute times (no drift). A consumer that falls behind by
        more than a period skips the missed ticks instead of bursting to catch up.
        """
        if not period > 0:
            raise ValueError(f"tick period must be positive, got {period!r}")
        due = self.now()
        while True:
            yield self.now()
            due += period
            now = self.now()
            if now - due > period:
                skipped = int((now - due) // period)
                log.debug("clock ticks at %.3g s sim fell behind, skipping %d", period, skipped)
                due += skipped * period
            await self.sleep_until(due)
