"""Plain rclpy nodes that know nothing of robovoice, run as separate processes by the tests.

    python tests/ros2/foreign_nodes.py projector fibonacci battery camera basic

Each named part is one ROS 2 node in this process (spun by one MultiThreadedExecutor). The
process prints ``ready`` once every part has made its services, actions and publishers, and
one line per request it receives (``request /projector/set_power data=True``), so a test can
tell what reached the robot. Services use queues 100 deep (the default 10 drops concurrent
calls).
"""

from __future__ import annotations

import math
import sys
import threading
import time
from typing import Any

import rclpy
from rclpy.action.server import ActionServer, CancelResponse, GoalResponse, ServerGoalHandle
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.node import Node
from rclpy.qos import QoSProfile
from sensor_msgs.msg import BatteryState, CompressedImage, Image
from std_srvs.srv import SetBool
from test_msgs.action import Fibonacci
from test_msgs.srv import BasicTypes

DEPTH = QoSProfile(depth=100)
STEP_S = 0.1


_PRINT = threading.Lock()


def say(text: str) -> None:
    """One whole line (callbacks run on several threads: lines must not interleave)."""
    with _PRINT:
        sys.stdout.write(text + "\n")
        sys.stdout.flush()


def projector() -> Node:
    node = Node("projector_driver")
    state = {"on": False}

    def set_power(request: Any, response: Any) -> Any:
        say(f"request /projector/set_power data={request.data}")
        state["on"] = bool(request.data)
        response.success = True
        response.message = "projector on" if request.data else "projector off"
        return response

    node.create_service(SetBool, "/projector/set_power", set_power, qos_profile=DEPTH,
                        callback_group=ReentrantCallbackGroup())
    return node


def basic() -> Node:
    node = Node("basic_types")

    def echo(request: Any, response: Any) -> Any:
        say(f"request /basic/echo int8={request.int8_value} float32={request.float32_value}")
        for name in request.get_fields_and_field_types():
            setattr(response, name, getattr(request, name))
        return response

    node.create_service(BasicTypes, "/basic/echo", echo, qos_profile=DEPTH)
    return node


def fibonacci() -> Node:
    """An action with feedback each step (0.1 s): rejects orders above 40, aborts order 13."""
    node = Node("fibonacci_server")

    def on_goal(goal: Any) -> GoalResponse:
        say(f"goal /fibonacci order={goal.order}")
        return GoalResponse.REJECT if goal.order > 40 else GoalResponse.ACCEPT

    def on_cancel(_: Any) -> CancelResponse:
        say("cancel /fibonacci")
        return CancelResponse.ACCEPT

    def execute(handle: ServerGoalHandle[Any, Any, Any]) -> Any:
        sequence = [0, 1]
        result = Fibonacci.Result()
        for _ in range(max(handle.request.order - 1, 0)):
            if handle.is_cancel_requested:
                handle.canceled()
                say("canceled /fibonacci")
                result.sequence = sequence
                return result
            sequence.append(sequence[-1] + sequence[-2])
            handle.publish_feedback(Fibonacci.Feedback(sequence=sequence))
            time.sleep(STEP_S)
        result.sequence = sequence
        if handle.request.order == 13:
            handle.abort()
        else:
            handle.succeed()
        return result

    ActionServer(node, Fibonacci, "/fibonacci", execute_callback=execute, goal_callback=on_goal,
                 cancel_callback=on_cancel, callback_group=ReentrantCallbackGroup(),
                 goal_service_qos_profile=DEPTH, result_service_qos_profile=DEPTH,
                 cancel_service_qos_profile=DEPTH)
    return node


def battery() -> Node:
    """sensor_msgs/BatteryState at 10 Hz, slowly discharging."""
    node = Node("battery_monitor")
    publisher = node.create_publisher(BatteryState, "/battery_state", 10)
    started = time.monotonic()

    def tick() -> None:
        msg = BatteryState()
        msg.header.stamp = node.get_clock().now().to_msg()
        msg.percentage = max(0.0, 0.87 - (time.monotonic() - started) / 3600.0)
        msg.voltage = 24.1
        msg.power_supply_status = BatteryState.POWER_SUPPLY_STATUS_DISCHARGING
        msg.present = True
        publisher.publish(msg)

    node.create_timer(0.1, tick)
    return node


def camera() -> Node:
    """A raw 16x12 rgb8 image and a compressed one at 5 Hz."""
    node = Node("camera_driver")
    raw = node.create_publisher(Image, "/camera/image_raw", 5)
    compressed = node.create_publisher(CompressedImage, "/camera/image/compressed", 5)
    width, height = 16, 12
    pixels = bytes(int(127 + 120 * math.sin((x + y) / 3.0)) for y in range(height) for x in range(width)
                   for _ in range(3))

    def tick() -> None:
        stamp = node.get_clock().now().to_msg()
        image = Image(width=width, height=height, encoding="rgb8", step=width * 3, data=list(pixels))
        image.header.stamp = stamp
        raw.publish(image)
        jpeg = CompressedImage(format="jpeg", data=list(b"\xff\xd8\xff\xe0fake-jpeg\xff\xd9"))
        jpeg.header.stamp = stamp
        compressed.publish(jpeg)

    node.create_timer(0.2, tick)
    return node


PARTS = {"projector": projector, "basic": basic, "fibonacci": fibonacci, "battery": battery, "camera": camera}


def main(argv: list[str]) -> int:
    rclpy.init()
    executor = MultiThreadedExecutor(num_threads=4)
    for part in argv:
        executor.add_node(PARTS[part]())
    say("ready")
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    try:
        spinner.join()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        executor.shutdown()
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
