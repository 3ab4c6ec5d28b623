"""Fixtures for the MCP server tests: a sim robot with its server, and the same over HTTP."""

from __future__ import annotations

from collections.abc import AsyncIterator
from pathlib import Path

import pytest

from robovoice.address import SimAddress
from robovoice.mcp_server import HttpEndpoint, RobotSide, http_server, open_robot_side

from .mcp_testkit import FAST


@pytest.fixture
def audit_path(tmp_path: Path) -> Path:
    return tmp_path / "audit.jsonl"


@pytest.fixture
async def robot(audit_path: Path) -> AsyncIterator[RobotSide]:
    """The sim robot (fast clock) and its RobotToolServer, following presence, with an audit log."""
    async with open_robot_side(SimAddress(speed=FAST), manifests=None, audit_log=audit_path) as running:
        yield running
    assert running.sim is not None and running.sim.failure is None


@pytest.fixture
async def http(robot: RobotSide) -> AsyncIterator[HttpEndpoint]:
    """`robot`'s server over streamable HTTP: a real uvicorn on a free loopback port."""
    async with http_server(robot.server, port=0) as endpoint:
        yield endpoint
