"""The executor of hosted nodes survives a failed callback: rclpy re-raises it in the spinning
thread, and before, that ended the serving of every node hosted on the session (seen in `bench
load --middleware ros2` when a node left while answering: `InvalidHandle` from send_response)."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from robovoice.middleware.ros2_bridge import RosBridge
from robovoice.middleware.ros2_config import Ros2Settings

from .ros2_testkit import RosWorld

import rclpy  # isort: skip
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from std_srvs.srv import Trigger

pytestmark = pytest.mark.integration


def _ask(domain: int, names: list[str], bound: float) -> list[str | None]:
    """A plain rclpy client (own context) calling each Trigger service once: the message, or None."""
    context = Context()
    rclpy.init(context=context, domain_id=domain)
    node = rclpy.create_node("asker", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    answers: list[str | None] = []
    try:
        for name in names:
            client: Any = node.create_client(Trigger, name)
            assert client.wait_for_service(timeout_sec=10), name
            future = client.call_async(Trigger.Request())
            executor.spin_until_future_complete(future, timeout_sec=bound)
            answers.append(future.result().message if future.done() else None)
    finally:
        executor.shutdown()
        node.destroy_node()
        context.try_shutdown()
    return answers


async def test_a_failed_callback_does_not_stop_the_hosted_nodes(ros: RosWorld) -> None:
    bridge = await asyncio.to_thread(RosBridge, Ros2Settings.from_uri(f"ros2://?domain_id={ros.domain}"),
                                     asyncio.get_running_loop())
    try:
        node = rclpy.create_node("hosted_raw", context=bridge.context)

        def boom(request: Any, response: Any) -> Any:
            raise RuntimeError("a callback that fails inside rclpy")

        def fine(request: Any, response: Any) -> Any:
            response.success, response.message = True, "still served"
            return response

        node.create_service(Trigger, "/host_test/boom", boom)
        node.create_service(Trigger, "/host_test/fine", fine)
        bridge.host_executor().add_node(node)
        answers = await asyncio.to_thread(_ask, ros.domain, ["/host_test/boom", "/host_test/fine"], 2.0)
        assert answers == [None, "still served"]
    finally:
        await asyncio.to_thread(bridge.close)
