"""The Middleware contract (tests/middleware/test_contract.py) run on ros2://: a robovoice node
hosted by one adapter, called through another on the same ROS 2 domain (two rclpy contexts)."""

from __future__ import annotations

from collections.abc import AsyncIterator

import pytest

from robovoice.middleware.base import NodeHost
from robovoice.middleware.ros2 import Ros2Middleware

from ..middleware.test_contract import (
    INFO,
    Pair,
    _count,
    _echo,
    test_action_feedback_then_result,
    test_action_timeout_cancels_it_on_the_node,
    test_call_round_trip,
    test_cancelling_the_caller_cancels_the_action_on_the_node,
    test_failures_pass_through_with_codes,
    test_missing_node_and_unknown_rpc,
    test_node_bug_becomes_internal_error,
    test_node_leaving_mid_action,
    test_presence,
    test_timeout,
    test_topics,
)
from .ros2_testkit import RosWorld

__all__ = [
    "test_action_feedback_then_result", "test_action_timeout_cancels_it_on_the_node", "test_call_round_trip",
    "test_cancelling_the_caller_cancels_the_action_on_the_node", "test_failures_pass_through_with_codes",
    "test_missing_node_and_unknown_rpc", "test_node_bug_becomes_internal_error", "test_node_leaving_mid_action",
    "test_presence", "test_timeout", "test_topics",
]


@pytest.fixture
async def pair(ros: RosWorld) -> AsyncIterator[Pair]:
    nodes = Ros2Middleware.from_uri(f"ros2://?domain_id={ros.domain}")
    client = Ros2Middleware.from_uri(f"ros2://?domain_id={ros.domain}")
    await nodes.start()
    try:
        await client.start()
        try:
            yield Pair(client, nodes)
        finally:
            await client.close()
    finally:
        await nodes.close()


@pytest.fixture
async def echo(pair: Pair) -> NodeHost:
    return await pair.host(INFO, {"echo": _echo}, {"count": _count})
