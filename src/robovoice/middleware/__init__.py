"""Middleware adapters, chosen by URI (`memory://`, `zenoh://...`)."""

from __future__ import annotations

from collections.abc import Callable

from robovoice.errors import ConfigError, UnsupportedURIError
from robovoice.middleware.base import Middleware
from robovoice.urls import split_uri


def _check_memory(uri: str) -> None:
    if uri != "memory://":  # one bus per process: nothing to choose, so nothing may be written
        raise ConfigError(f"middleware URI {uri!r}: the in-process bus takes no host, path or options; "
                          f"write memory://")


def _memory(uri: str) -> Middleware:
    from robovoice.middleware.memory import MemoryMiddleware

    _check_memory(uri)
    return MemoryMiddleware(uri)


def _zenoh(uri: str) -> Middleware:
    from robovoice.middleware.zenoh import ZenohMiddleware  # needs the [zenoh] extra

    return ZenohMiddleware.from_uri(uri)


def _ros2(uri: str) -> Middleware:
    from robovoice.middleware.ros2 import Ros2Middleware  # needs the [ros2] extra

    return Ros2Middleware.from_uri(uri)


ADAPTERS: dict[str, Callable[[str], Middleware]] = {"memory": _memory, "zenoh": _zenoh, "ros2": _ros2}


def check_middleware_uri(uri: str) -> None:
    """Check `uri` without creating its adapter (no extra needed): the scheme always, and the
    whole URI for the adapters whose URI parsers are plain code (memory, zenoh, ros2); any
    other checks its own when opened."""
    scheme = split_uri(uri, "middleware URI").scheme if "://" in uri else ""
    if scheme not in ADAPTERS:
        raise UnsupportedURIError(uri, [f"{s}://" for s in ADAPTERS], what="middleware URI")
    if scheme == "memory":
        _check_memory(uri)
    elif scheme == "zenoh":
        from robovoice.middleware.zenoh_config import ZenohSettings

        ZenohSettings.from_uri(uri)
    elif scheme == "ros2":
        from robovoice.middleware.ros2_config import Ros2Settings

        Ros2Settings.from_uri(uri)


def open_middleware(uri: str) -> Middleware:
    """Create (not yet start) the middleware adapter for `uri`."""
    scheme = split_uri(uri, "middleware URI").scheme if "://" in uri else ""
    factory = ADAPTERS.get(scheme)
    if factory is None:
        raise UnsupportedURIError(uri, [f"{s}://" for s in ADAPTERS], what="middleware URI")
    return factory(uri)


__all__ = ["ADAPTERS", "Middleware", "check_middleware_uri", "open_middleware"]
