"""The simulated robot hardware that the sim nodes drive: pose, motors, battery, safety.

On a real robot the navigation stack, the base controller and localization are separate
processes that share one physical body. In the sim that body is this object: the sim
nodes of one process share it, and talk to the *outside* only through the middleware.
`Motion` is the motor controller's view of one drive: a stop from the base (or a cancel,
or a new goal) halts it, and the drive loop notices at once.
"""

from __future__ import annotations

import asyncio
import logging
import math
from dataclasses import dataclass

from robovoice.sim.clock import SimClock
from robovoice.sim.world import DOCK, Point, place

log = logging.getLogger(__name__)

DEFAULT_MAX_SPEED_MPS = 0.5
HARDWARE_MAX_SPEED_MPS = 1.5
DRAIN_PER_METRE = 0.1  # percent of battery per metre driven
IDLE_DRAIN_PER_S = 0.005  # percent per sim second, off the dock
CHARGE_PER_S = 0.25  # percent per sim second, on the dock
BATTERY_CRITICAL = 5.0  # below this the robot only drives to the dock
BATTERY_EMPTY = 1.0  # at or below this it does not drive at all
FULL_VOLTAGE = 25.2
EMPTY_VOLTAGE = 21.0


@dataclass(frozen=True, slots=True)
class Pose:
    x: float
    y: float
    heading_deg: float

    @property
    def point(self) -> Point:
        return Point(self.x, self.y)


class Motion:
    """One drive as the motor controller sees it: can be halted, reports when it ended."""

    def __init__(self, label: str) -> None:
        self.label = label
        self.halt_reason: str | None = None
        self._halted = asyncio.Event()
        self._ended = asyncio.Event()

    @property
    def halted(self) -> bool:
        return self._halted.is_set()

    def halt(self, reason: str) -> None:
        if not self._halted.is_set():
            self.halt_reason = reason
            self._halted.set()

    async def pause(self, clock: SimClock, sim_seconds: float) -> bool:
        """Wait `sim_seconds` or until halted; True if halted."""
        if self._halted.is_set():
            return True
        try:
            async with asyncio.timeout(clock.to_real(sim_seconds)):
                await self._halted.wait()
        except TimeoutError:
            return False
        return True

    def end(self) -> None:
        self._ended.set()

    async def wait_ended(self, timeout_s: float) -> bool:
        """Wait (real seconds, bounded) until the drive loop has ended; True if it has."""
        try:
            async with asyncio.timeout(timeout_s):
                await self._ended.wait()
        except TimeoutError:
            return False
        return True


class SimBody:
    """Pose, motion, battery and safety settings of the one simulated robot."""

    def __init__(self, clock: SimClock, *, start: str = DOCK, battery_percent: float = 80.0) -> None:
        self.clock = clock
        position = place(start).position
        self.pose = Pose(position.x, position.y, 90.0)
        self.battery_percent = battery_percent
        self.max_speed_mps = DEFAULT_MAX_SPEED_MPS
        self.collision_avoidance = True
        self.odometer_m = 0.0
        self._motion: Motion | None = None

    # --- motion ----------------------------------------------------------------------
    @property
    def motion(self) -> Motion | None:
        """The drive under way, if any."""
        return self._motion

    @property
    def moving(self) -> bool:
        return self._motion is not None

    def begin_motion(self, label: str) -> Motion:
        """Start a drive; a drive still under way is halted ("replaced by ...")."""
        if self._motion is not None:
            self._motion.halt(f"replaced by a new drive ({label})")
        self._motion = Motion(label)
        return self._motion

    def end_motion(self, motion: Motion) -> None:
        if self._motion is motion:
            self._motion = None
        motion.end()

    def halt(self, reason: str) -> Motion | None:
        """Stop all motion now; returns the drive that was halted, if any."""
        motion = self._motion
        if motion is not None:
            log.info("halting %s: %s", motion.label, reason)
            motion.halt(reason)
        return motion

    def move_to(self, point: Point, heading_deg: float) -> None:
        """The motors moved the robot to `point`; the battery pays for the distance."""
        distance = self.pose.point.distance_to(point)
        self.odometer_m += distance
        self.drain(distance * DRAIN_PER_METRE)
        self.pose = Pose(point.x, point.y, heading_deg % 360)

    # --- battery ---------------------------------------------------------------------
    def drain(self, percent: float) -> None:
        self.battery_percent = min(100.0, max(0.0, self.battery_percent - percent))

    @property
    def on_dock(self) -> bool:
        return self.pose.point.distance_to(place(DOCK).position) <= 0.3

    @property
    def charging(self) -> bool:
        return self.on_dock and not self.moving and self.battery_percent < 100.0

    @property
    def voltage(self) -> float:
        return EMPTY_VOLTAGE + (FULL_VOLTAGE - EMPTY_VOLTAGE) * self.battery_percent / 100.0

    def heading_towards(self, a: Point, b: Point) -> float:
        if a.distance_to(b) < 1e-9:
            return self.pose.heading_deg
        return math.degrees(math.atan2(b.y - a.y, b.x - a.x)) % 360
