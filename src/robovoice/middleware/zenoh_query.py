"""A Zenoh query in flight, seen from the event loop: `Exchange`.

Whatever concerns one query (its replies, the end of the query, action feedback, the
node leaving, the adapter closing) arrives as an item in the exchange's queue, on the
event loop (through `LoopBridge`). The caller awaits `next()` under its own timeout.
"""

from __future__ import annotations

import asyncio
import collections
from collections.abc import Mapping
from dataclasses import dataclass

import zenoh

from robovoice.middleware.base import JSON, Feedback
from robovoice.middleware.zenoh_bridge import LoopBridge
from robovoice.middleware.zenoh_codec import ENCODING, encode


@dataclass(frozen=True, slots=True)
class Answer:
    """A reply: `ok` (a result) or an error reply, with its payload and attachment bytes."""

    ok: bool
    payload: bytes
    attachment: bytes | None = None


@dataclass(frozen=True, slots=True)
class Finished:
    """Zenoh finished the query: every queryable answered, or none matched, or it timed out."""


@dataclass(frozen=True, slots=True)
class NodeGone:
    """The node's liveliness token disappeared while the query was in flight."""


@dataclass(frozen=True, slots=True)
class Closed:
    """The adapter was closed while the query was in flight."""


Item = Answer | Finished | NodeGone | Closed | Feedback


class Exchange:
    """One query to one node (see the module docstring). Items wait in a deque; the caller
    waits on one future at a time (cheaper than an `asyncio.Queue` plus `asyncio.timeout`
    on the hot path of every RPC)."""

    def __init__(self, node: str, goal_id: str | None = None) -> None:
        self.node = node
        self.goal_id = goal_id
        self._items: collections.deque[Item] = collections.deque()
        self._waiter: asyncio.Future[Item] | None = None

    def push(self, item: Item) -> None:
        waiter = self._waiter
        if waiter is not None and not waiter.done():
            waiter.set_result(item)
        else:
            self._items.append(item)

    def pending(self) -> int:
        """Items that arrived and were not taken yet."""
        return len(self._items)

    async def next(self, timeout: float | None = None) -> Item:
        """The next item; `TimeoutError` if none comes within `timeout` seconds."""
        if self._items:
            return self._items.popleft()
        loop = asyncio.get_running_loop()
        waiter: asyncio.Future[Item] = loop.create_future()
        self._waiter = waiter
        timer = None if timeout is None else loop.call_later(timeout, _expire, waiter)
        try:
            return await waiter
        finally:
            self._waiter = None
            if timer is not None:
                timer.cancel()


def _expire(waiter: asyncio.Future[Item]) -> None:
    if not waiter.done():
        waiter.set_exception(TimeoutError())


def answer_of(reply: zenoh.Reply) -> Answer:
    """A reply as plain bytes (run on Zenoh's thread: no Zenoh object reaches the loop)."""
    sample = reply.ok
    if sample is not None:
        attachment = sample.attachment
        return Answer(True, sample.payload.to_bytes(), None if attachment is None else attachment.to_bytes())
    error = reply.err
    return Answer(False, b"" if error is None else error.payload.to_bytes())


JSON_ENCODING = zenoh.Encoding(ENCODING)
"""Parsed once, not per call."""


def send_query(
    session: zenoh.Session,
    bridge: LoopBridge,
    exchange: Exchange,
    key: str,
    args: Mapping[str, JSON] | None,
    *,
    timeout: float,
    parameters: Mapping[str, str] | None = None,
) -> None:
    """Send ``GET key?parameters`` with `args` as JSON; replies go to `exchange`.

    Zenoh's own timeout is a little longer than the caller's, so the caller's deadline
    decides and Zenoh only cleans up. Each reply reaches `exchange` with one loop wake-up;
    `Finished` comes only when the query ended without any reply. Raises `TypeError`/
    `ValueError` for arguments JSON cannot carry, `zenoh.ZError` when the session is closed.
    """
    payload = None if args is None else encode(dict(args))
    selector = zenoh.Selector(key, dict(parameters)) if parameters else key
    session.get(
        selector,
        bridge.replies(answer_of, exchange.push, lambda: exchange.push(Finished())),
        payload=payload,
        encoding=JSON_ENCODING if payload is not None else None,
        consolidation=zenoh.ConsolidationMode.NONE,
        timeout=timeout + 1.0,
    )
