"""The one place where Zenoh's threads hand work to the event loop.

Zenoh runs callbacks (samples, queries, replies, liveliness changes) on its own threads.
Every handler the Zenoh adapter gives to Zenoh comes from `LoopBridge.handler`: the
callback only calls `loop.call_soon_threadsafe`, and the real work runs on the event loop
that started the adapter, as the Middleware protocol promises.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Protocol, TypeVar, cast

import zenoh

log = logging.getLogger(__name__)

T = TypeVar("T")


class LoopBridge:
    """Posts Zenoh callbacks onto one event loop."""

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        self._loop = loop

    @property
    def loop(self) -> asyncio.AbstractEventLoop:
        return self._loop

    def post(self, fn: Callable[..., object], *args: object) -> None:
        """Run ``fn(*args)`` on the loop soon. Safe from any thread; a no-op once the loop is closed."""
        try:
            self._loop.call_soon_threadsafe(fn, *args)
        except RuntimeError:  # the loop is closed: nobody is left to tell
            log.debug("event loop closed; dropped a Zenoh callback for %r", fn)

    def handler(
        self,
        on_item: Callable[[T], object],
        on_drop: Callable[[], object] | None = None,
    ) -> zenoh.handlers.Callback[T]:
        """A Zenoh callback handler that runs `on_item` (and `on_drop` when Zenoh is done
        with the handler: a query finished, a subscriber undeclared) on the loop."""

        def item(value: T) -> None:
            self.post(on_item, value)

        def drop() -> None:
            if on_drop is not None:
                self.post(on_drop)

        # indirect=False: run on Zenoh's thread; posting is all we do there, so no extra thread
        return zenoh.handlers.Callback(item, drop, indirect=False)


# --- typed shims: zenoh's stubs leave these methods without a return type ----------------


class _Undeclarable(Protocol):
    def undeclare(self) -> None: ...


class _Droppable(Protocol):
    def drop(self) -> None: ...


class _Closable(Protocol):
    def close(self) -> None: ...


def undeclare(entity: object) -> None:
    """Undeclare a Zenoh subscriber, queryable, publisher or liveliness token."""
    cast(_Undeclarable, entity).undeclare()


def finish(query: zenoh.Query) -> None:
    """Finish a query (the querier then sees the end of its replies)."""
    cast(_Droppable, query).drop()


def close_session(session: zenoh.Session) -> None:
    cast(_Closable, session).close()
