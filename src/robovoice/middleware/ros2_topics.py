"""Topic subscriptions: ROS 2 messages → `Message` (JSON values) on the event loop.

Messages are converted on the executor thread and handed over in batches; when the event
loop falls behind a fast topic (a 30 Hz camera), the oldest undelivered messages are dropped
(`MAX_PENDING`), so memory stays flat. The subscription is best-effort (it matches both
reliable and best-effort publishers, as sensor drivers often are).
"""

from __future__ import annotations

import json
import logging
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Any

from robovoice.errors import ConfigError
from robovoice.middleware.base import Message
from robovoice.middleware.ros2_bindings import SnapshotBinding
from robovoice.middleware.ros2_bridge import RosBridge
from robovoice.middleware.ros2_host import topic_name
from robovoice.middleware.ros2_types import import_type, stamp_of, to_json

from rclpy.qos import QoSProfile, ReliabilityPolicy  # isort: skip

log = logging.getLogger(__name__)

MAX_PENDING = 8
RAW_IMAGE_INTERVAL_S = 0.5
"""Raw `sensor_msgs/Image` frames are PNG-encoded here, ~50 ms for 640 x 480 on one core: at most
one frame per this interval is converted (the newer ones in between are dropped), so a 30 Hz
camera does not take a core and a half. `CompressedImage` frames are cheap: all are taken."""


class TopicSubscription:
    """One rclpy subscription delivering converted messages to `callback` on the loop."""

    def __init__(self, bridge: RosBridge, topic: str, msg_type: Any, convert: Callable[[Any], Any],
                 callback: Callable[[Message], None], *, ros_topic: str | None = None, hosted: bool = False) -> None:
        self._bridge = bridge
        self._topic = topic
        self._convert = convert
        self._callback = callback
        self._pending: deque[Message] = deque(maxlen=MAX_PENDING)
        self._lock = threading.Lock()
        self._scheduled = False
        self._closed = False
        raw_image = getattr(msg_type, "__module__", "").startswith("sensor_msgs.") and msg_type.__name__ == "Image"
        self._interval = RAW_IMAGE_INTERVAL_S if raw_image else 0.0
        self._last = -float("inf")
        qos = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
        self._hosted = hosted
        self._sub = bridge.node.create_subscription(msg_type, ros_topic or topic, self._receive, qos,
                                                    callback_group=bridge.group)

    def _receive(self, msg: Any) -> None:  # on the executor thread
        if self._hosted:
            self._receive_hosted(msg)
            return
        if self._interval:
            now = time.monotonic()
            if now - self._last < self._interval:
                return
            self._last = now
        stamp = stamp_of(msg) or time.time()
        try:
            value = self._convert(msg)
        except Exception:
            log.exception("cannot convert a message on %s", self._topic)
            return
        with self._lock:
            self._pending.append(Message(self._topic, value, stamp))
            if self._scheduled:
                return
            self._scheduled = True
        self._bridge.post(self._deliver)

    def _receive_hosted(self, msg: Any) -> None:
        try:
            body = json.loads(msg.data)
            message = Message(self._topic, body["value"], float(body["stamp"]))
        except (ValueError, KeyError, TypeError):
            log.warning("not a robovoice JSON message on %s", self._topic)
            return
        with self._lock:
            self._pending.append(message)
            if self._scheduled:
                return
            self._scheduled = True
        self._bridge.post(self._deliver)

    def _deliver(self) -> None:  # on the loop
        with self._lock:
            batch = list(self._pending)
            self._pending.clear()
            self._scheduled = False
        for message in batch:
            if self._closed:
                return
            try:
                self._callback(message)
            except Exception:
                log.exception("subscriber of %s failed", self._topic)

    def close(self) -> None:
        if self._closed:
            return
        self._closed = True
        try:
            self._bridge.node.destroy_subscription(self._sub)
        except Exception:  # the node is already gone (middleware closed first)
            log.debug("subscription of %s already destroyed", self._topic)


def subscribe_topic(bridge: RosBridge, topic: str, binding: SnapshotBinding | None,
                    callback: Callable[[Message], None]) -> TopicSubscription:
    """Subscribe with the manifest's type for `topic`, else the type the graph shows. A name
    without a leading slash is a robovoice topic of a hosted node (`ros2_host`)."""
    if not topic.startswith("/"):
        from std_msgs.msg import String

        return TopicSubscription(bridge, topic, String, to_json, callback, ros_topic=topic_name(topic), hosted=True)
    if binding is not None:
        return TopicSubscription(bridge, topic, binding.message, binding.value, callback)
    types = dict(bridge.node.get_topic_names_and_types()).get(topic)
    if not types:
        raise ConfigError(f"topic {topic!r}: its type is unknown (no manifest names it and no publisher is seen)")
    return TopicSubscription(bridge, topic, import_type(types[0]), to_json, callback)
