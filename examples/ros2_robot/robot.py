"""A plain ROS 2 robot that knows nothing of robovoice: four rclpy nodes with standard types.

    python examples/ros2_robot/robot.py [--speed X]

- ``navigation``: the action ``/navigate_to_pose`` (``nav2_msgs/action/NavigateToPose``, Nav2's
  fields and type name) drives at 0.5 m/s (times ``--speed``) to the goal pose, with feedback
  (current pose, distance remaining, times) and cancellation; goals outside the 12 x 8 m map
  are aborted. ``/navigation/stop`` (``std_srvs/srv/Trigger``) stops any drive.
- ``projector``: the service ``/projector/set_power`` (``std_srvs/srv/SetBool``).
- ``battery``: ``/battery_state`` (``sensor_msgs/msg/BatteryState``) at 10 Hz.
- ``camera``: ``/camera/image_raw`` (``sensor_msgs/msg/Image``, 64 x 48 rgb8) at 5 Hz.

Services are made with queues 100 deep (ROS 2's default of 10 drops concurrent calls). The
manifests in ``manifests/`` give these nodes a voice (see README.md here and docs/ros2.md).
"""

from __future__ import annotations

import argparse
import math
import threading
import time
from typing import Any

import rclpy
from geometry_msgs.msg import PoseStamped
from nav2_msgs.action import NavigateToPose
from rclpy.action.server import ActionServer, CancelResponse, GoalResponse, ServerGoalHandle
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.node import Node
from rclpy.qos import QoSProfile
from sensor_msgs.msg import BatteryState, Image
from std_srvs.srv import SetBool, Trigger

SERVICES = QoSProfile(depth=100)
MAP_X, MAP_Y = 12.0, 8.0
SPEED_M_S = 0.5
TICK_S = 0.2


class Navigation(Node):
    """Drives in a straight line to the goal pose, one goal at a time (a new goal replaces it)."""

    def __init__(self, speed: float) -> None:
        super().__init__("navigation")
        self.speed = speed
        self.x, self.y = 1.0, 1.0  # at the charging dock
        self.lock = threading.Lock()
        self.active: ServerGoalHandle[Any, Any, Any] | None = None
        self.stop_requested = False
        group = ReentrantCallbackGroup()
        ActionServer(self, NavigateToPose, "/navigate_to_pose", execute_callback=self.execute,
                     goal_callback=self.on_goal, cancel_callback=lambda _: CancelResponse.ACCEPT,
                     callback_group=group, goal_service_qos_profile=SERVICES,
                     result_service_qos_profile=SERVICES, cancel_service_qos_profile=SERVICES)
        self.create_service(Trigger, "/navigation/stop", self.on_stop, qos_profile=SERVICES, callback_group=group)

    def on_goal(self, goal: Any) -> GoalResponse:
        frame = goal.pose.header.frame_id
        self.get_logger().info(f"goal ({goal.pose.pose.position.x}, {goal.pose.pose.position.y}) in {frame!r}")
        return GoalResponse.ACCEPT if frame in ("map", "") else GoalResponse.REJECT

    def on_stop(self, _: Any, response: Any) -> Any:
        with self.lock:
            driving = self.active is not None
            self.stop_requested = driving
        response.success = True
        response.message = "stopped" if driving else "was not driving"
        return response

    def execute(self, handle: ServerGoalHandle[Any, Any, Any]) -> Any:
        with self.lock:
            self.active = handle
            self.stop_requested = False
        tx, ty = handle.request.pose.pose.position.x, handle.request.pose.pose.position.y
        result = NavigateToPose.Result()
        started = time.monotonic()
        try:
            if not (0.0 <= tx <= MAP_X and 0.0 <= ty <= MAP_Y):
                result.error_code, result.error_msg = NavigateToPose.Result.UNKNOWN, "the goal is outside the map"
                handle.abort()
                return result
            while (distance := math.hypot(tx - self.x, ty - self.y)) > 1e-6:
                if handle.is_cancel_requested or self.stop_requested or not handle.is_active:
                    if handle.is_cancel_requested:
                        handle.canceled()
                    else:
                        handle.abort()
                    result.error_msg = "stopped"
                    return result
                step = min(distance, SPEED_M_S * self.speed * TICK_S)
                self.x += (tx - self.x) / distance * step
                self.y += (ty - self.y) / distance * step
                feedback = NavigateToPose.Feedback()
                feedback.current_pose = self.pose()
                feedback.distance_remaining = float(distance - step)
                elapsed = time.monotonic() - started
                feedback.navigation_time.sec = int(elapsed)
                remaining = (distance - step) / (SPEED_M_S * self.speed)
                feedback.estimated_time_remaining.sec = int(remaining)
                handle.publish_feedback(feedback)
                time.sleep(TICK_S)
            handle.succeed()
            return result
        finally:
            with self.lock:
                if self.active is handle:
                    self.active = None

    def pose(self) -> PoseStamped:
        pose = PoseStamped()
        pose.header.frame_id = "map"
        pose.header.stamp = self.get_clock().now().to_msg()
        pose.pose.position.x, pose.pose.position.y = self.x, self.y
        pose.pose.orientation.w = 1.0
        return pose


class Projector(Node):
    def __init__(self) -> None:
        super().__init__("projector")
        self.on = False
        self.create_service(SetBool, "/projector/set_power", self.set_power, qos_profile=SERVICES)

    def set_power(self, request: Any, response: Any) -> Any:
        self.on = bool(request.data)
        response.success = True
        response.message = "the projector is on" if self.on else "the projector is off"
        return response


class Battery(Node):
    def __init__(self) -> None:
        super().__init__("battery")
        self.publisher = self.create_publisher(BatteryState, "/battery_state", 10)
        self.started = time.monotonic()
        self.create_timer(0.1, self.tick)

    def tick(self) -> None:
        msg = BatteryState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.percentage = max(0.05, 0.82 - (time.monotonic() - self.started) / 7200.0)
        msg.voltage = 25.2
        msg.power_supply_status = BatteryState.POWER_SUPPLY_STATUS_DISCHARGING
        msg.present = True
        self.publisher.publish(msg)


class Camera(Node):
    WIDTH, HEIGHT = 64, 48

    def __init__(self) -> None:
        super().__init__("camera")
        self.publisher = self.create_publisher(Image, "/camera/image_raw", 5)
        self.frame = 0
        self.create_timer(0.2, self.tick)

    def tick(self) -> None:
        self.frame += 1
        w, h = self.WIDTH, self.HEIGHT
        data = bytearray(w * h * 3)
        for y in range(h):
            for x in range(w):
                i = (y * w + x) * 3
                data[i], data[i + 1], data[i + 2] = (x * 4) % 256, (y * 5) % 256, (self.frame * 8) % 256
        msg = Image(width=w, height=h, encoding="rgb8", step=w * 3, data=bytes(data))
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.header.frame_id = "camera"
        self.publisher.publish(msg)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=1.0, help="drive this many times faster (tests, demos)")
    args = parser.parse_args()
    rclpy.init()
    executor = MultiThreadedExecutor(num_threads=4)
    for node in (Navigation(args.speed), Projector(), Battery(), Camera()):
        executor.add_node(node)
    print("robot ready: navigation, projector, battery, camera", flush=True)
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        executor.shutdown()
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
