"""Fixtures for the fault tests: child processes that are always reaped (`spawn`, from the
distributed tests)."""

from tests.distributed.conftest import spawn

__all__ = ["spawn"]
