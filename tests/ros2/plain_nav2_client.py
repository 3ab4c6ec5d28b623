"""A plain rclpy process that knows nothing of robovoice and drives the simulated robot through
the standard interfaces `robovoice sim --middleware ros2://…` serves (run by test_ros2_sim_standard):

    python tests/ros2/plain_nav2_client.py

1. ``/projector/set_power`` (std_srvs/srv/SetBool) with data=true;
2. a NavigateToPose goal at the kitchen's pose (2.0, 6.5), to arrival;
3. a goal far from every named place (20, 20), which the sim aborts;
4. a goal at the front door (11.5, 4.0), cancelled after three feedback messages; then two
   ``/robot_pose`` (geometry_msgs/PoseStamped) messages 0.5 s apart show whether it stopped.

One line per event: ``setbool <success> <message>``, ``feedback <distance_remaining> <x> <y>
<navigation_time_s>``, ``result <label> <status> <error_code> <error_msg>``, ``cancel <accepted>``,
``pose <x> <y>``; ``done`` at the end. Every wait is bounded (``failed <what>`` and exit 1).
"""

from __future__ import annotations

import sys
import time
from typing import Any

import rclpy
from action_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav2_msgs.action import NavigateToPose
from rclpy.action.client import ActionClient
from rclpy.client import Client
from rclpy.node import Node
from rclpy.task import Future
from std_srvs.srv import SetBool

BOUND_S = 20.0


def say(text: str) -> None:
    sys.stdout.write(text + "\n")
    sys.stdout.flush()


def wait(node: Node, future: Future[Any], what: str) -> Any:
    rclpy.spin_until_future_complete(node, future, timeout_sec=BOUND_S)
    if not future.done():
        say(f"failed {what}")
        sys.exit(1)
    return future.result()


def goal_at(x: float, y: float) -> Any:
    goal = NavigateToPose.Goal()
    goal.pose.header.frame_id = "map"
    goal.pose.pose.position.x, goal.pose.pose.position.y = x, y
    goal.pose.pose.orientation.w = 1.0
    return goal


def main() -> int:
    rclpy.init()
    node = rclpy.create_node("plain_nav2_client")
    projector: Client[Any, Any] = node.create_client(SetBool, "/projector/set_power")
    navigate: ActionClient[Any, Any, Any] = ActionClient(node, NavigateToPose, "/navigate_to_pose")
    if not projector.wait_for_service(timeout_sec=BOUND_S) or not navigate.wait_for_server(timeout_sec=BOUND_S):
        say("failed discovery")
        return 1
    answer = wait(node, projector.call_async(SetBool.Request(data=True)), "set_power")
    say(f"setbool {answer.success} {answer.message}")

    feedback: list[Any] = []

    def heard(message: Any) -> None:
        f = message.feedback
        feedback.append(f)
        seconds = f.navigation_time.sec + f.navigation_time.nanosec / 1e9
        say(f"feedback {f.distance_remaining:.2f} {f.current_pose.pose.position.x:.2f} "
            f"{f.current_pose.pose.position.y:.2f} {seconds:.3f}")

    def drive(label: str, x: float, y: float, cancel_after: int | None = None) -> None:
        feedback.clear()
        handle = wait(node, navigate.send_goal_async(goal_at(x, y), feedback_callback=heard), f"{label} goal")
        if not handle.accepted:
            say(f"result {label} rejected")
            return
        result = handle.get_result_async()
        if cancel_after is not None:
            deadline = time.monotonic() + BOUND_S
            while len(feedback) < cancel_after and time.monotonic() < deadline:
                rclpy.spin_once(node, timeout_sec=0.1)
            cancelled = wait(node, handle.cancel_goal_async(), f"{label} cancel")
            say(f"cancel {len(cancelled.goals_canceling) == 1}")
        done = wait(node, result, f"{label} result")
        status = {GoalStatus.STATUS_SUCCEEDED: "succeeded", GoalStatus.STATUS_ABORTED: "aborted",
                  GoalStatus.STATUS_CANCELED: "canceled"}.get(done.status, str(done.status))
        say(f"result {label} {status} {done.result.error_code} {done.result.error_msg}")

    drive("kitchen", 2.0, 6.5)
    drive("nowhere", 20.0, 20.0)
    drive("front_door", 11.5, 4.0, cancel_after=3)

    poses: list[Any] = []
    node.create_subscription(PoseStamped, "/robot_pose", poses.append, 10)
    for _ in range(2):
        poses.clear()
        deadline = time.monotonic() + BOUND_S
        while not poses and time.monotonic() < deadline:
            rclpy.spin_once(node, timeout_sec=0.1)
        if not poses:
            say("failed pose")
            return 1
        say(f"pose {poses[-1].pose.position.x:.2f} {poses[-1].pose.position.y:.2f}")
        time.sleep(0.5)
    say("done")
    node.destroy_node()
    rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
