"""Standard ROS 2 mirrors of well-known robovoice topics, published beside the JSON ones by a
hosted node (`ros2_host`), so that plain ROS 2 tools see the simulated robot in the types
they know:

| robovoice topic (value) | ROS 2 topic | type |
|---|---|---|
| `battery` (`{"percent", "charging", "voltage"}`) | `/battery_state` | `sensor_msgs/msg/BatteryState` |
| `pose` (`{"x", "y", "heading_deg", ...}`) | `/robot_pose` | `geometry_msgs/msg/PoseStamped` (frame `map`) |
| `camera` (`{"mime_type": "image/jpeg", "data"}`) | `/camera/image/compressed` | `sensor_msgs/msg/CompressedImage` |

A value that does not have the expected shape is not mirrored (the JSON topic still carries it).
"""

from __future__ import annotations

import base64
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import BatteryState, CompressedImage

from robovoice.middleware.base import JSON


@dataclass(frozen=True, slots=True)
class Mirror:
    ros_topic: str
    msg_type: Any
    build: Callable[[Mapping[str, Any]], Any]


def _stamp(msg: Any, stamp: float) -> Any:
    msg.header.stamp.sec = int(stamp)
    msg.header.stamp.nanosec = min(int((stamp - int(stamp)) * 1e9), 999_999_999)
    return msg


def _battery(value: Mapping[str, Any]) -> Any:
    msg = BatteryState()
    msg.percentage = float(value["percent"]) / 100.0
    msg.voltage = float(value.get("voltage", math.nan))
    msg.power_supply_status = (BatteryState.POWER_SUPPLY_STATUS_CHARGING if value.get("charging")
                               else BatteryState.POWER_SUPPLY_STATUS_DISCHARGING)
    msg.present = True
    return msg


def _pose(value: Mapping[str, Any]) -> Any:
    msg = PoseStamped()
    msg.header.frame_id = "map"
    msg.pose.position.x, msg.pose.position.y = float(value["x"]), float(value["y"])
    yaw = math.radians(float(value.get("heading_deg", 0.0)))
    msg.pose.orientation.z, msg.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return msg


def _image(value: Mapping[str, Any]) -> Any:
    mime = str(value["mime_type"])
    return CompressedImage(format=mime.removeprefix("image/"), data=base64.b64decode(str(value["data"])))


MIRRORS: Mapping[str, Mirror] = {
    "battery": Mirror("/battery_state", BatteryState, _battery),
    "pose": Mirror("/robot_pose", PoseStamped, _pose),
    "camera": Mirror("/camera/image/compressed", CompressedImage, _image),
}


def mirrored(topic: str, value: JSON, stamp: float) -> Any | None:
    """The standard message for a well-known robovoice topic's value, or None."""
    mirror = MIRRORS.get(topic)
    if mirror is None or not isinstance(value, Mapping):
        return None
    try:
        return _stamp(mirror.build(value), stamp)
    except (KeyError, TypeError, ValueError):
        return None
