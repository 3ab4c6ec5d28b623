"""robovoice's own nodes (the sim robot) hosted on ROS 2, and how clients reach them.

A hosted node becomes one rclpy node. Its RPCs are services ``/robovoice/<node>/<rpc>`` and its
actions action servers of the same names, of the JSON types of the ``robovoice_msgs`` interface
package (``srv/Call``, ``action/Run``: JSON arguments in, JSON result or error out, progress as
feedback); its topics are ``std_msgs/String`` JSON on ``/robovoice/topics/<topic>``; and it
announces its `NodeInfo` (with its manifest) on the latched ``/robovoice/nodes``. Well-known
RPCs also get standard servers (`ros2_standard_servers`: NavigateToPose, SetBool) and well-known
topics standard mirrors (`ros2_standard`). So `robovoice
serve --middleware ros2://…` finds it with no manifest folder, exactly as over Zenoh.

Handlers run on the event loop; the service and action callbacks wait for them on the host's
own multi-threaded executor (`RosBridge.host_executor`), so a long action never holds up the
adapter's client side.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import json
import logging
import math
import re
import time
from collections.abc import Awaitable, Callable, Mapping
from typing import Any

from robovoice.errors import MiddlewareError, RobotFailure
from robovoice.middleware.base import JSON, ActionHandler, Feedback, NodeInfo, RpcHandler, RpcInfo
from robovoice.middleware.ros2_bridge import RosBridge
from robovoice.middleware.ros2_standard import MIRRORS, mirrored
from robovoice.middleware.ros2_standard_servers import serve_standard

import rclpy  # isort: skip
from rclpy.action.server import ActionServer, CancelResponse, GoalResponse, ServerGoalHandle
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import String

log = logging.getLogger(__name__)

ANNOUNCE_TOPIC = "/robovoice/nodes"
TOPIC_PREFIX = "/robovoice/topics/"
HOST_CALL_S = 3600.0
"""The longest a hosted handler may run (the caller's own timeout is usually far shorter)."""
ANNOUNCE_QOS = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL, reliability=ReliabilityPolicy.RELIABLE)
SERVICES = QoSProfile(depth=100)
_UNSAFE = re.compile(r"[^A-Za-z0-9_]")


def ros_part(name: str) -> str:
    """A robovoice name as one ROS 2 name token (letters, digits, underscores)."""
    token = _UNSAFE.sub("_", name)
    return token if token[:1].isalpha() else f"n{token}"


def host_node_name(node: str) -> str:
    """The ROS node name of a hosted robovoice node."""
    return f"robovoice_{ros_part(node)}"


def rpc_name(node: str, rpc: str) -> str:
    return f"/robovoice/{ros_part(node)}/{ros_part(rpc)}"


def topic_name(topic: str) -> str:
    return TOPIC_PREFIX + "/".join(ros_part(p) for p in topic.split("/") if p)


def interfaces() -> tuple[Any, Any]:
    """``robovoice_msgs``' Call and Run, or a `MiddlewareError` saying how to build them."""
    try:
        from robovoice_msgs.action import Run
        from robovoice_msgs.srv import Call
    except ImportError:
        raise MiddlewareError(
            "hosting robovoice nodes on ROS 2 needs the robovoice_msgs interface package: "
            "bash scripts/build_ros2_interfaces.sh") from None
    return Call, Run


def info_to_json(info: NodeInfo) -> str:
    return json.dumps({
        "name": info.name, "topics": list(info.topics), "manifest": info.manifest,
        "manifest_source": info.manifest_source,
        "rpcs": [{"name": r.name, "kind": r.kind, "params": list(r.params), "description": r.description}
                 for r in info.rpcs],
    }, default=dict)


def info_from_json(text: str) -> NodeInfo:
    data = json.loads(text)
    rpcs = tuple(RpcInfo(r["name"], r["kind"], tuple(r["params"]), r.get("description", "")) for r in data["rpcs"])
    return NodeInfo(data["name"], rpcs, tuple(data["topics"]), data.get("manifest"), data.get("manifest_source", ""))


async def _coroutine(awaitable: Awaitable[JSON]) -> JSON:
    return await awaitable


def _failure_json(exc: BaseException) -> str:
    if isinstance(exc, concurrent.futures.CancelledError | asyncio.CancelledError):
        return json.dumps({"error": "cancelled", "message": "the action was cancelled", "hint": None, "details": {}})
    if isinstance(exc, RobotFailure):
        return json.dumps(exc.to_dict(), default=str)
    return json.dumps({"error": "internal_error", "message": f"{type(exc).__name__}: {exc}",
                       "hint": "this is a fault in the robot software; tell the user", "details": {}})


class Ros2NodeHost:
    """One robovoice node served on ROS 2 (see the module docstring). Made on the event loop."""

    def __init__(self, bridge: RosBridge, info: NodeInfo, rpcs: Mapping[str, RpcHandler],
                 actions: Mapping[str, ActionHandler]) -> None:
        call_type, run_type = interfaces()
        self._bridge = bridge
        self._info = info
        self._loop = asyncio.get_running_loop()
        node = rclpy.create_node(host_node_name(info.name), context=bridge.context,
                                 enable_rosout=False, start_parameter_services=False)
        self._node: Node | None = node
        group = ReentrantCallbackGroup()
        self._run_type = run_type
        for name, handler in rpcs.items():
            node.create_service(call_type, rpc_name(info.name, name), self._service(handler),
                                      qos_profile=SERVICES, callback_group=group)
        self._servers = [
            ActionServer(node, run_type, rpc_name(info.name, name), execute_callback=self._execute(handler),
                         goal_callback=lambda _: GoalResponse.ACCEPT, cancel_callback=lambda _: CancelResponse.ACCEPT,
                         callback_group=group, goal_service_qos_profile=SERVICES,
                         result_service_qos_profile=SERVICES, cancel_service_qos_profile=SERVICES)
            for name, handler in actions.items()
        ]
        # NavigateToPose and SetBool for plain ROS 2 clients, beside the JSON ones
        self._standard = serve_standard(self, node, group, SERVICES, info.name, rpcs, actions)
        self._running: set[concurrent.futures.Future[JSON]] = set()
        self._publishers: dict[str, Any] = {}
        self._mirrors: dict[str, Any] = {}
        for topic in info.topics:
            self._publishers[topic] = node.create_publisher(String, topic_name(topic), 10)
        self._announcer = node.create_publisher(String, ANNOUNCE_TOPIC, ANNOUNCE_QOS)
        self._announcer.publish(String(data=info_to_json(info)))
        bridge.host_executor().add_node(node)

    @property
    def info(self) -> NodeInfo:
        return self._info

    def publish(self, topic: str, value: JSON, stamp: float | None = None) -> None:
        if self._node is None:  # left
            return
        publisher = self._publishers.get(topic)
        if publisher is None:
            publisher = self._publishers[topic] = self._node.create_publisher(String, topic_name(topic), 10)
        when = time.time() if stamp is None else stamp
        publisher.publish(String(data=json.dumps({"value": value, "stamp": when}, default=str)))
        standard = mirrored(topic, value, when)
        if standard is not None:
            mirror = self._mirrors.get(topic)
            if mirror is None:
                mirror = self._mirrors[topic] = self._node.create_publisher(
                    type(standard), MIRRORS[topic].ros_topic, 10)
            mirror.publish(standard)

    async def leave(self) -> None:
        node, self._node = self._node, None
        if node is None:
            return
        for running in list(self._running):  # callers get node_unavailable; the threads come free
            running.cancel()
        self._bridge.host_executor().remove_node(node)
        for server in self._servers:
            server.destroy()
        for standard in self._standard:
            standard.destroy()
        await asyncio.to_thread(node.destroy_node)

    def failure(self, exc: BaseException) -> str:
        """A handler's failure as the JSON error a caller gets."""
        if self._node is None:  # cancelled by leave()
            return json.dumps({"error": "node_unavailable", "message": f"node {self._info.name!r} left",
                               "hint": "the robot part went offline; tell the user", "details": {}})
        return _failure_json(exc)

    def wait_for(self, work: Awaitable[JSON], cancelled: Callable[[], bool] | None = None) -> JSON:
        """Run a handler's coroutine on the event loop and wait for it (on an executor thread);
        `cancelled`, polled every 20 ms, cancels it. Raises what the handler raised."""
        done = asyncio.run_coroutine_threadsafe(_coroutine(work), self._loop)
        self._running.add(done)
        try:
            while cancelled is not None and not done.done():
                if cancelled():
                    done.cancel()
                    break
                time.sleep(0.02)
            return done.result(HOST_CALL_S)
        finally:
            self._running.discard(done)

    def _service(self, handler: RpcHandler) -> Any:
        def serve(request: Any, response: Any) -> Any:  # on a host executor thread
            try:
                args = json.loads(request.arguments or "{}")
                response.result = json.dumps(self.wait_for(handler(args)), default=str)
            except BaseException as exc:  # every failure goes back to the caller as a JSON error
                response.error = self.failure(exc)
            return response
        return serve

    def _execute(self, handler: ActionHandler) -> Any:
        def execute(goal: ServerGoalHandle[Any, Any, Any]) -> Any:  # on a host executor thread
            result = self._run_type.Result()
            args = json.loads(goal.request.arguments or "{}")

            async def feedback(item: Feedback) -> None:
                goal.publish_feedback(self._run_type.Feedback(
                    progress=float(item.progress), total=math.nan if item.total is None else float(item.total),
                    message=item.message, data=json.dumps(dict(item.data), default=str)))

            try:
                result.result = json.dumps(self.wait_for(handler(args, feedback), lambda: goal.is_cancel_requested),
                                           default=str)
                goal.succeed()
            except BaseException as exc:  # cancelled, a robot failure, a bug: the caller gets JSON
                result.error = self.failure(exc)
                if goal.is_cancel_requested:
                    goal.canceled()
                else:
                    goal.abort()
            return result
        return execute
