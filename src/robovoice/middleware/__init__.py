"""Middleware adapters, chosen by URI (`memory://`, `zenoh://...`)."""

from __future__ import annotations

from collections.abc import Callable
from urllib.parse import urlsplit

from robovoice.errors import UnsupportedURIError
from robovoice.middleware.base import Middleware


def _memory(uri: str) -> Middleware:
    from robovoice.middleware.memory import MemoryMiddleware

    return MemoryMiddleware(uri)


def _zenoh(uri: str) -> Middleware:
    from robovoice.middleware.zenoh import ZenohMiddleware  # needs the [zenoh] extra

    return ZenohMiddleware.from_uri(uri)


def _ros2(uri: str) -> Middleware:
    from robovoice.middleware.ros2 import Ros2Middleware  # needs the [ros2] extra

    return Ros2Middleware.from_uri(uri)


ADAPTERS: dict[str, Callable[[str], Middleware]] = {"memory": _memory, "zenoh": _zenoh, "ros2": _ros2}


def open_middleware(uri: str) -> Middleware:
    """Create (not yet start) the middleware adapter for `uri`."""
    scheme = urlsplit(uri).scheme
    factory = ADAPTERS.get(scheme)
    if factory is None:
        raise UnsupportedURIError(uri, [f"{s}://" for s in ADAPTERS])
    return factory(uri)


__all__ = ["ADAPTERS", "Middleware", "open_middleware"]
