"""Shared manifests and nodes for the manifest tests."""

from __future__ import annotations

import copy
from typing import Any

import pytest

from robovoice.middleware.base import NodeInfo, RpcInfo

NAVIGATION: dict[str, Any] = {
    "node": "navigation",
    "description": "Driving around the home",
    "tools": [
        {
            "name": "navigate_to",
            "rpc": "navigate",
            "description": "Drive to a known place.",
            "parameters": {
                "type": "object",
                "properties": {"target": {"type": "string", "description": "a known place"}},
                "required": ["target"],
            },
        },
        {
            "name": "return_to_dock",
            "rpc": "navigate",
            "description": "Drive back to the charging dock.",
            "defaults": {"target": "charging dock"},
        },
        {"name": "cancel_navigation", "rpc": "cancel", "description": "Stop the current drive."},
    ],
    "snapshots": [
        {"name": "get_robot_pose", "topic": "pose", "description": "Where the robot is.", "max_age_s": 1.0}
    ],
}

NAV_INFO = NodeInfo(
    "navigation",
    rpcs=(
        RpcInfo("navigate", "action", ("target", "speed")),
        RpcInfo("cancel", "rpc", ()),
        RpcInfo("set_max_speed", "rpc", ("speed",)),
    ),
    topics=("pose", "map"),
)


@pytest.fixture
def nav() -> dict[str, Any]:
    """A fresh copy of the navigation manifest, free to modify."""
    return copy.deepcopy(NAVIGATION)


@pytest.fixture
def nav_info() -> NodeInfo:
    return NAV_INFO
