"""Shared fixtures for the LLM tests: some of the sim robot's tools, a free port."""

from __future__ import annotations

import socket

import pytest

from robovoice.llm.base import ToolSpec

NAVIGATE_TO = ToolSpec(
    "navigate_to",
    "Drive the robot to a known place in the home.",
    {
        "type": "object",
        "properties": {"target": {"type": "string", "description": "the place, e.g. kitchen"}},
        "required": ["target"],
    },
)
STOP_ROBOT = ToolSpec("stop_robot", "Stop all motion now.", {"type": "object", "properties": {}})
SET_PROJECTOR = ToolSpec(
    "set_projector_power",
    "Switch the projector on or off.",
    {"type": "object", "properties": {"on": {"type": "boolean"}}, "required": ["on"]},
)


@pytest.fixture
def tools() -> list[ToolSpec]:
    return [NAVIGATE_TO, STOP_ROBOT, SET_PROJECTOR]


@pytest.fixture
def unused_port() -> int:
    """A loopback port nothing listens on (bound, then released)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        port: int = sock.getsockname()[1]
    return port
