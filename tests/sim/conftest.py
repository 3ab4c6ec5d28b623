"""Fixtures for the sim robot tests: a memory bus, fast sim robots, topic inboxes."""

from __future__ import annotations

from collections.abc import AsyncIterator, Awaitable, Callable, Collection

import pytest

from robovoice.middleware.memory import MemoryMiddleware
from robovoice.sim import SimClock, SimRobot, start_sim_robot

from .sim_testkit import SPEED, FeedbackLog, Inbox, StartRobot


@pytest.fixture
async def bus() -> AsyncIterator[MemoryMiddleware]:
    bus = MemoryMiddleware()
    await bus.start()
    yield bus
    await bus.close()


@pytest.fixture
async def start(bus: MemoryMiddleware) -> AsyncIterator[StartRobot]:
    """Start a sim robot on `bus` (all nodes unless `nodes=` says otherwise); stopped after the test."""
    robots: list[SimRobot] = []

    async def _start(*, nodes: Collection[str] | None = None, speed: float = SPEED) -> SimRobot:
        robot = await start_sim_robot(bus, speed=speed, nodes=nodes)
        robots.append(robot)
        return robot

    yield _start
    for robot in robots:
        await robot.stop()
        assert robot.failure is None, robot.failure


@pytest.fixture
def make_inbox(bus: MemoryMiddleware) -> Callable[[str, SimClock], Awaitable[Inbox]]:
    """`await make_inbox(topic, clock)`: subscribe an `Inbox` to `topic` on the bus."""

    async def _make(topic: str, clock: SimClock) -> Inbox:
        box = Inbox(clock)
        await bus.subscribe(topic, box)
        return box

    return _make


@pytest.fixture
def feedback() -> FeedbackLog:
    return FeedbackLog()
