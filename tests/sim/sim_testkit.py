"""Helpers for the sim robot tests: topic inboxes and feedback logs with bounded waits."""

from __future__ import annotations

import asyncio
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Any

from robovoice.middleware.base import Feedback, Message
from robovoice.sim import SimClock, SimRobot

SPEED = 40.0  # sim seconds per real second in these tests
BOUND_S = 5.0  # the longest any test waits for an event (real seconds)

StartRobot = Callable[..., Awaitable[SimRobot]]


@dataclass
class Received:
    sim_time: float
    value: Any


@dataclass
class Inbox:
    """Every message of one topic, stamped with the sim time it arrived."""

    clock: SimClock
    items: list[Received] = field(default_factory=list)
    _changed: asyncio.Event = field(default_factory=asyncio.Event)

    def __call__(self, message: Message) -> None:
        self.items.append(Received(self.clock.now(), message.value))
        self._changed.set()

    async def wait_for(self, predicate: Callable[[list[Received]], bool], bound_s: float = BOUND_S) -> None:
        async with asyncio.timeout(bound_s):
            while not predicate(self.items):
                self._changed.clear()
                await self._changed.wait()

    async def wait_count(self, n: int, bound_s: float = BOUND_S) -> list[Received]:
        await self.wait_for(lambda items: len(items) >= n, bound_s)
        return self.items[:n]

    @property
    def values(self) -> list[Any]:
        return [item.value for item in self.items]


@dataclass
class FeedbackLog:
    """Collects an action's feedback; `wait_for` waits (bounded) for a condition on it."""

    items: list[Feedback] = field(default_factory=list)
    _changed: asyncio.Event = field(default_factory=asyncio.Event)

    async def __call__(self, feedback: Feedback) -> None:
        self.items.append(feedback)
        self._changed.set()

    async def wait_for(self, predicate: Callable[[list[Feedback]], bool], bound_s: float = BOUND_S) -> None:
        async with asyncio.timeout(bound_s):
            while not predicate(self.items):
                self._changed.clear()
                await self._changed.wait()
