"""Node `navigation`: drive to named places, with feasibility checks and progress.

- action `drive_to(target)`: checks first (unknown place -> `unknown_target`, the balcony
  -> `unreachable`, battery too low -> `battery_low`/`battery_empty`, already there -> a
  success that says so), then drives along the hallway route at the body's maximum speed
  (0.5 m/s by default), moving the pose and sending feedback at 4 Hz sim time. A new
  drive replaces one under way. A halted drive (the `cancel` RPC, the base's `stop`, a
  new goal) ends with `RobotFailure(code="cancelled")`; cancelling the caller's task
  stops the robot too.
  The result names the place as resolved (`{"target": "living room", "arrived": …}` for
  "lounge").
- RPC `list_targets()`: the known places, which are reachable, where the robot is.
- RPC `cancel()`: halts the drive under way; with none, fails with `not_driving` (so the
  model can say "I wasn't driving" rather than claim it stopped something).
- RPC `get_status()`: driving or not, target, distances, nearest place.
- topic `map` (1 Hz sim): the places with their coordinates and the drivable ways
  (`world.map_message`), as a real robot publishes its map.
"""

from __future__ import annotations

import itertools
import logging
from collections.abc import Mapping
from dataclasses import dataclass

from robovoice.errors import CancelledByRobotError, RobotFailure
from robovoice.middleware.base import (
    JSON,
    ActionHandler,
    Feedback,
    FeedbackSender,
    NodeHost,
    NodeInfo,
    RpcHandler,
    RpcInfo,
)
from robovoice.sim.body import BATTERY_CRITICAL, BATTERY_EMPTY, SimBody
from robovoice.sim.node import check_args, make_node_info, str_arg
from robovoice.sim.world import (
    ARRIVAL_TOLERANCE_M,
    DOCK,
    PLACES,
    Place,
    Point,
    find_place,
    known_places,
    map_message,
    nearest_place,
    route,
    route_length,
)

log = logging.getLogger(__name__)

NAME = "navigation"
MAP_TOPIC = "map"
MAP_PERIOD_S = 1.0
TICK_S = 0.1
FEEDBACK_PERIOD_S = 0.25
HALT_WAIT_S = 2.0  # real seconds a cancel waits for the drive loop to end

RPCS = (
    RpcInfo("drive_to", "action", ("target",), "drive to a named place"),
    RpcInfo("list_targets", "rpc", (), "the known places"),
    RpcInfo("cancel", "rpc", (), "cancel the drive under way"),
    RpcInfo("get_status", "rpc", (), "whether the robot is driving, and where to"),
)
_RPC = {r.name: r for r in RPCS}


def _distance_text(metres: float) -> str:
    return f"{round(metres)} m" if metres >= 1.5 else f"{metres:.1f} m"


def _point_along(points: list[Point], distance: float) -> tuple[Point, Point, Point]:
    """The point `distance` metres along the polyline, and the segment it lies on."""
    for a, b in itertools.pairwise(points):
        length = a.distance_to(b)
        if distance <= length:
            f = distance / length if length else 1.0
            return Point(a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f), a, b
        distance -= length
    return points[-1], points[-2], points[-1]


@dataclass
class _Drive:
    place: Place
    total_m: float
    done_m: float = 0.0

    @property
    def remaining_m(self) -> float:
        return max(0.0, self.total_m - self.done_m)


class NavigationNode:
    name = NAME

    def __init__(self, body: SimBody) -> None:
        self._body = body
        self._clock = body.clock
        self._drive: _Drive | None = None

    @property
    def driving_target(self) -> str | None:
        return self._drive.place.name if self._drive else None

    def node_info(self) -> NodeInfo:
        return make_node_info(NAME, RPCS, (MAP_TOPIC,))

    def rpc_handlers(self) -> Mapping[str, RpcHandler]:
        return {"list_targets": self._list_targets, "cancel": self._cancel, "get_status": self._get_status}

    def action_handlers(self) -> Mapping[str, ActionHandler]:
        return {"drive_to": self._drive_to}

    async def run(self, host: NodeHost) -> None:
        """Publish the map (drives run in the callers' action calls)."""
        async for _ in self._clock.ticks(MAP_PERIOD_S):
            host.publish(MAP_TOPIC, map_message())

    # --- checks ----------------------------------------------------------------------
    def _resolve(self, target: str) -> Place:
        place = find_place(target)
        if place is None:
            known = known_places(reachable_only=True)
            raise RobotFailure(
                f"unknown place {target!r}; known places: {', '.join(known)}",
                code="unknown_target",
                hint="tell the user you do not know that place, name the known places and ask which one they mean",
                details={"target": target, "known_places": known},
            )
        if place.blocked is not None:
            raise RobotFailure(
                f"cannot drive to the {place.name}: {place.blocked}",
                code="unreachable",
                hint=f"tell the user the robot cannot get to the {place.name} ({place.blocked})",
                details={"target": place.name, "reason": place.blocked},
            )
        return place

    def _check_battery(self, place: Place) -> None:
        percent = round(self._body.battery_percent, 1)
        if percent <= BATTERY_EMPTY:
            raise RobotFailure(
                f"the battery is empty ({percent} %): the robot cannot drive",
                code="battery_empty",
                hint="tell the user the robot needs to be carried or pushed to its charging dock",
                details={"battery_percent": percent},
            )
        if percent < BATTERY_CRITICAL and place.name != DOCK:
            raise RobotFailure(
                f"the battery is critically low ({percent} %): the robot only drives to its charging dock",
                code="battery_low",
                hint="tell the user the battery is too low and offer to return to the charging dock",
                details={"battery_percent": percent, "threshold_percent": BATTERY_CRITICAL},
            )

    # --- handlers --------------------------------------------------------------------
    async def _drive_to(self, args: dict[str, JSON], feedback: FeedbackSender) -> JSON:
        check_args(args, _RPC["drive_to"])
        place = self._resolve(str_arg(args, "drive_to", "target"))
        self._check_battery(place)
        previous = self._body.halt(f"replaced by a new drive to the {place.name}")
        if previous is not None:
            await previous.wait_ended(HALT_WAIT_S)
        start = self._body.pose.point
        if start.distance_to(place.position) <= ARRIVAL_TOLERANCE_M:
            return {"target": place.name, "arrived": place.name, "where": place.where, "distance_m": 0.0,
                    "duration_s": 0.0, "already_there": True, "message": f"already at the {place.name}"}

        motion = self._body.begin_motion(f"drive to the {place.name}")
        points = route(start, place.position)
        drive = _Drive(place, route_length(points))
        self._drive = drive
        started = last = self._clock.now()
        log.info("driving to the %s (%.1f m)", place.name, drive.total_m)
        try:
            await feedback(self._feedback(drive))
            next_tick, next_feedback = started + TICK_S, started + FEEDBACK_PERIOD_S
            while drive.remaining_m > 0:
                # wake for the next motion step or the next feedback, whichever is due first
                if await motion.pause(self._clock, min(next_tick, next_feedback) - self._clock.now()):
                    raise self._halted(drive, motion.halt_reason or "halted")
                now = self._clock.now()
                step = min(self._body.max_speed_mps * (now - last), drive.remaining_m)
                last = now
                drive.done_m += step
                point, a, b = _point_along(points, drive.done_m)
                self._body.move_to(point, self._body.heading_towards(a, b))
                if self._body.battery_percent <= 0:
                    raise RobotFailure(
                        f"the battery ran out {_distance_text(drive.remaining_m)} before the {place.name}",
                        code="battery_empty",
                        hint="tell the user the robot stopped because its battery is empty",
                        details={"target": place.name, "remaining_m": round(drive.remaining_m, 2)},
                    )
                if now >= next_tick:
                    next_tick = max(next_tick + TICK_S, now)
                if now >= next_feedback or drive.remaining_m <= 0:
                    await feedback(self._feedback(drive))
                    # a fixed schedule keeps the rate; a late loop catches up by one at most
                    next_feedback = max(next_feedback + FEEDBACK_PERIOD_S, now)
        finally:
            if self._drive is drive:
                self._drive = None
            self._body.end_motion(motion)
        duration = self._clock.now() - started
        log.info("arrived at the %s after %.1f s", place.name, duration)
        # `target` is the place as the robot resolved it ("lounge" -> "living room")
        return {"target": place.name, "arrived": place.name, "where": place.where,
                "distance_m": round(drive.total_m, 2), "duration_s": round(duration, 1)}

    def _feedback(self, drive: _Drive) -> Feedback:
        pose = self._body.pose
        message = (f"arrived at the {drive.place.name}" if drive.remaining_m <= 0
                   else f"{_distance_text(drive.remaining_m)} to the {drive.place.name}")
        return Feedback(
            progress=round(drive.done_m, 3),
            total=round(drive.total_m, 3),
            message=message,
            data={"target": drive.place.name, "remaining_m": round(drive.remaining_m, 2),
                  "x": round(pose.x, 2), "y": round(pose.y, 2), "heading_deg": round(pose.heading_deg, 1)},
        )

    def _halted(self, drive: _Drive, reason: str) -> CancelledByRobotError:
        return CancelledByRobotError(
            f"the drive to the {drive.place.name} was cancelled ({reason}), "
            f"{_distance_text(drive.remaining_m)} before arriving",
            hint="the robot has stopped; tell the user where it is if they ask",
            details={"target": drive.place.name, "reason": reason,
                     "distance_done_m": round(drive.done_m, 2), "remaining_m": round(drive.remaining_m, 2)},
        )

    async def _list_targets(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["list_targets"])
        return {
            "places": known_places(reachable_only=True),
            "unreachable": {p.name: p.blocked for p in PLACES if p.blocked is not None},
            "nearest_place": nearest_place(self._body.pose.point).name,
        }

    async def _cancel(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["cancel"])
        drive, motion = self._drive, self._body.motion
        if drive is None or motion is None:
            raise RobotFailure(
                "the robot is not driving: there is nothing to cancel",
                code="not_driving",
                hint="tell the user the robot is already standing still",
                details={"nearest_place": nearest_place(self._body.pose.point).name},
            )
        motion.halt("cancelled on request")
        await motion.wait_ended(HALT_WAIT_S)
        return {"cancelled": True, "target": drive.place.name, "remaining_m": round(drive.remaining_m, 2),
                "nearest_place": nearest_place(self._body.pose.point).name}

    async def _get_status(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["get_status"])
        drive = self._drive
        return {
            "driving": drive is not None,
            "target": drive.place.name if drive else None,
            "distance_m": round(drive.total_m, 2) if drive else None,
            "remaining_m": round(drive.remaining_m, 2) if drive else None,
            "nearest_place": nearest_place(self._body.pose.point).name,
        }
