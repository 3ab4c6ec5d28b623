"""Fixtures for the ROS 2 tests: each test gets its own ROS_DOMAIN_ID (150..230), logs in tmp."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from .ros2_testkit import RosWorld, next_domain


@pytest.fixture
def ros(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[RosWorld]:
    log_dir = tmp_path / "ros-logs"
    monkeypatch.setenv("ROS_LOG_DIR", str(log_dir))
    world = RosWorld(next_domain(), log_dir)
    try:
        yield world
    finally:
        world.close()
