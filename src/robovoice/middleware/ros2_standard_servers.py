"""Standard ROS 2 servers beside a hosted node's JSON ones (`ros2_host`), so that plain ROS 2
clients drive the simulated robot with the types they know:

| hosted robovoice RPC | ROS 2 | type |
|---|---|---|
| `navigation.drive_to` (action) | action `/navigate_to_pose` | `nav2_msgs/action/NavigateToPose` |
| `projector.set_power` (RPC) | service `/projector/set_power` | `std_srvs/srv/SetBool` |

The sim's navigation drives only to its named places (`sim.world`), so a NavigateToPose goal
goes to the place nearest its pose, if one lies within `GOAL_TOLERANCE_M`; a goal farther
from every place, or in a frame other than ``map``, is aborted with an `error_msg` naming the
places. Feedback carries `current_pose`, `distance_remaining`, `navigation_time` and an
estimate of the time left; a cancel halts the drive (the robot stops); the result's
`error_code` is `NONE` on arrival and `UNKNOWN` with the robot's error in `error_msg` otherwise.
SetBool's `message` is the RPC's JSON result (or its error's message, with `success` false).

Without the `nav2_msgs` interface package (scripts/build_ros2_interfaces.sh) the action is
not served, and said so once in the log; the JSON action is unaffected.
"""

from __future__ import annotations

import json
import logging
import math
import time
from collections.abc import Awaitable, Callable, Mapping
from typing import Any, Protocol

from rclpy.action.server import ActionServer, CancelResponse, GoalResponse, ServerGoalHandle
from rclpy.callback_groups import CallbackGroup
from rclpy.node import Node
from rclpy.qos import QoSProfile

from robovoice.errors import RobotFailure
from robovoice.middleware.base import JSON, ActionHandler, Feedback, RpcHandler
from robovoice.sim.world import PLACES, Place, Point

log = logging.getLogger(__name__)

NAVIGATE_ACTION = "/navigate_to_pose"
PROJECTOR_SERVICE = "/projector/set_power"
GOAL_TOLERANCE_M = 1.0
"""How far a NavigateToPose goal may lie from a named place and still mean it."""
MAP_FRAMES = ("map", "")


class Waiter(Protocol):
    """What a standard server needs of its host: run a handler on the event loop and wait."""

    def wait_for(self, work: Awaitable[JSON], cancelled: Callable[[], bool] | None = None) -> JSON: ...

    def failure(self, exc: BaseException) -> str: ...


def goal_place(frame_id: str, x: float, y: float) -> Place:
    """The named place a goal pose means, or a `RobotFailure` that says why there is none."""
    if frame_id not in MAP_FRAMES:
        raise RobotFailure(f"goal frame {frame_id!r} is not supported: give the pose in the 'map' frame",
                           code="invalid_arguments", details={"frame_id": frame_id})
    nearest = min(PLACES, key=lambda p: p.position.distance_to(Point(x, y)))
    if nearest.position.distance_to(Point(x, y)) > GOAL_TOLERANCE_M:
        places = ", ".join(f"{p.name} ({p.position.x:g}, {p.position.y:g})" for p in PLACES if p.reachable)
        raise RobotFailure(
            f"no named place within {GOAL_TOLERANCE_M:g} m of ({x:g}, {y:g}): the simulated robot drives only "
            f"to its places: {places}", code="unknown_target", details={"x": x, "y": y})
    return nearest


def serve_standard(host: Waiter, node: Node, group: CallbackGroup, qos: QoSProfile, name: str,
                   rpcs: Mapping[str, RpcHandler], actions: Mapping[str, ActionHandler]) -> list[Any]:
    """The standard servers of hosted node `name` (see the module docstring); destroy them on leave."""
    made: list[Any] = []
    if name == "projector" and "set_power" in rpcs:
        from std_srvs.srv import SetBool

        made.append(node.create_service(SetBool, PROJECTOR_SERVICE, _set_bool(host, rpcs["set_power"]),
                                        qos_profile=qos, callback_group=group))
    if name == "navigation" and "drive_to" in actions:
        try:
            from nav2_msgs.action import NavigateToPose
        except ImportError:
            log.info("no %s action: the nav2_msgs interface package is not installed "
                     "(bash scripts/build_ros2_interfaces.sh)", NAVIGATE_ACTION)
            return made
        execute = _navigate(host, actions["drive_to"], NavigateToPose)
        made.append(ActionServer(
            node, NavigateToPose, NAVIGATE_ACTION, execute_callback=execute,
            goal_callback=lambda _: GoalResponse.ACCEPT, cancel_callback=lambda _: CancelResponse.ACCEPT,
            callback_group=group, goal_service_qos_profile=qos, result_service_qos_profile=qos,
            cancel_service_qos_profile=qos))
    return made


def _set_bool(host: Waiter, handler: RpcHandler) -> Callable[[Any, Any], Any]:
    def serve(request: Any, response: Any) -> Any:  # on a host executor thread
        try:
            response.message = json.dumps(host.wait_for(handler({"on": bool(request.data)})), default=str)
            response.success = True
        except BaseException as exc:  # every failure goes back as success=false with the reason
            response.success = False
            response.message = str(json.loads(host.failure(exc)).get("message", exc))
        return response
    return serve


def _seconds(duration: Any, seconds: float) -> Any:
    seconds = max(0.0, seconds) if math.isfinite(seconds) else 0.0
    duration.sec = int(seconds)
    duration.nanosec = min(int((seconds - int(seconds)) * 1e9), 999_999_999)
    return duration


def _navigate(host: Waiter, handler: ActionHandler, action: Any) -> Callable[[ServerGoalHandle[Any, Any, Any]], Any]:
    def execute(goal: ServerGoalHandle[Any, Any, Any]) -> Any:  # on a host executor thread
        result = action.Result()
        pose = goal.request.pose
        started = time.monotonic()

        async def feedback(item: Feedback) -> None:
            data = item.data
            message = action.Feedback()
            message.current_pose.header.frame_id = "map"
            message.current_pose.pose.position.x = float(data.get("x", math.nan))
            message.current_pose.pose.position.y = float(data.get("y", math.nan))
            yaw = math.radians(float(data.get("heading_deg", 0.0)))
            message.current_pose.pose.orientation.z = math.sin(yaw / 2)
            message.current_pose.pose.orientation.w = math.cos(yaw / 2)
            remaining = float(data.get("remaining_m", math.nan))
            message.distance_remaining = remaining
            elapsed = time.monotonic() - started
            _seconds(message.navigation_time, elapsed)
            done_m = float(item.progress)
            _seconds(message.estimated_time_remaining, elapsed * remaining / done_m if done_m > 0 else math.nan)
            goal.publish_feedback(message)

        try:
            place = goal_place(pose.header.frame_id, pose.pose.position.x, pose.pose.position.y)
            host.wait_for(handler({"target": place.name}, feedback), lambda: goal.is_cancel_requested)
            result.error_code = action.Result.NONE
            goal.succeed()
        except BaseException as exc:  # cancelled, a robot failure, a bug: error_msg says which
            result.error_code = action.Result.UNKNOWN
            error = json.loads(host.failure(exc))
            result.error_msg = f"{error.get('error')}: {error.get('message')}"
            if goal.is_cancel_requested:
                goal.canceled()
            else:
                goal.abort()
        return result
    return execute
