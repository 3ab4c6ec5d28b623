"""Fixtures for the ROS 2 tests: each test gets its own ROS_DOMAIN_ID (150..230), logs in tmp."""

from __future__ import annotations

import importlib.util
from collections.abc import Iterator
from pathlib import Path

import pytest

from ..installed import require
from .ros2_testkit import RosWorld, next_domain


@pytest.fixture(scope="session", autouse=True)
def ros2_installed() -> None:
    """rclpy and the message packages (the ros2 extra), robovoice_msgs (hosted nodes) and nav2_msgs (the example)."""
    require(importlib.util.find_spec("rclpy") is not None, "ROS 2 (rclpy)", "pip install 'robovoice[ros2]'")
    for package in ("robovoice_msgs", "nav2_msgs"):
        require(importlib.util.find_spec(package) is not None, f"the ROS 2 interface package {package}",
                "bash scripts/build_ros2_interfaces.sh")


@pytest.fixture
def ros(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[RosWorld]:
    log_dir = tmp_path / "ros-logs"
    monkeypatch.setenv("ROS_LOG_DIR", str(log_dir))
    world = RosWorld(next_domain(), log_dir)
    try:
        yield world
    finally:
        world.close()
