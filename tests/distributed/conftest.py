"""Fixtures for multi-process tests (helpers in `helpers.py`)."""

from __future__ import annotations

import contextlib
import subprocess
from collections.abc import Callable, Iterator

import pytest

from .helpers import Child


@pytest.fixture
def spawn() -> Iterator[Callable[..., Child]]:
    """Start child processes; every one is stopped (or killed) at teardown."""
    children: list[Child] = []

    def start(name: str, argv: list[str]) -> Child:
        child = Child(name, argv)
        children.append(child)
        return child

    yield start
    for child in children:
        with contextlib.suppress(OSError, subprocess.SubprocessError):  # already gone
            child.stop()
