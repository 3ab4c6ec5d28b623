"""The one place where Zenoh's threads hand work to the event loop.

Zenoh runs callbacks (samples, queries, replies, liveliness changes) on its own threads.
Every handler the Zenoh adapter gives to Zenoh comes from `LoopBridge.handler` (or `.stream`,
for topics: bounded and batched; or `.replies`, for query replies: their bytes are copied out
on Zenoh's thread): the callback only copies data and calls `loop.call_soon_threadsafe`, and
the real work runs on the event loop that started the adapter, as the Middleware protocol
promises. Each post wakes the loop (~40-60 us on a loaded 2-core box), so the round-trip
paths post once per reply and never for nothing.
"""

from __future__ import annotations

import asyncio
import collections
import logging
import threading
from collections.abc import Callable
from typing import Generic, Protocol, TypeVar, cast

import zenoh

log = logging.getLogger(__name__)

T = TypeVar("T")
U = TypeVar("U")


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

    def replies(
        self,
        convert: Callable[[zenoh.Reply], U],
        on_reply: Callable[[U], object],
        on_none: Callable[[], object],
    ) -> zenoh.handlers.Callback[zenoh.Reply]:
        """A handler for a query's replies, cheaper on the round trip than `handler`: each
        reply is turned into plain data by `convert` on Zenoh's thread (copying bytes out;
        `convert` must touch nothing the loop owns), so the loop is woken once, with the
        data ready, and runs `on_reply`; `on_none` runs on the loop only when the query
        ended without any reply (after an answer, the end of the query wakes nobody)."""
        answered = False

        def item(reply: zenoh.Reply) -> None:
            nonlocal answered
            answered = True  # Zenoh ends a query after its last reply callback returned
            self.post(on_reply, convert(reply))

        def drop() -> None:
            if not answered:
                self.post(on_none)

        return zenoh.handlers.Callback(item, drop, indirect=False)


    def stream(self, on_item: Callable[[T], object], *, limit: int, what: str) -> zenoh.handlers.Callback[T]:
        """A handler for a stream of samples (a topic): items wait in a bounded buffer and
        are handed to `on_item` on the loop in batches, one loop wake-up per batch. If the
        loop falls `limit` items behind, the oldest are dropped (and counted in a warning)
        rather than letting memory grow."""
        batch = _Batch(self, on_item, limit, what)
        return zenoh.handlers.Callback(batch.push, indirect=False)


class _Batch(Generic[T]):
    """The bounded buffer behind `LoopBridge.stream`."""

    def __init__(self, bridge: LoopBridge, on_item: Callable[[T], object], limit: int, what: str) -> None:
        self._bridge = bridge
        self._on_item = on_item
        self._what = what
        self._items: collections.deque[T] = collections.deque(maxlen=limit)
        self._lock = threading.Lock()
        self._scheduled = False
        self._dropped = 0

    def push(self, item: T) -> None:  # on a Zenoh thread
        with self._lock:
            if len(self._items) == self._items.maxlen:
                self._dropped += 1
            self._items.append(item)
            if self._scheduled:
                return
            self._scheduled = True
        self._bridge.post(self._drain)

    def _drain(self) -> None:  # on the loop
        with self._lock:
            items = list(self._items)
            self._items.clear()
            self._scheduled = False
            dropped, self._dropped = self._dropped, 0
        if dropped:
            log.warning("%s: the event loop fell behind; dropped the %d oldest messages", self._what, dropped)
        for item in items:
            self._on_item(item)


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
