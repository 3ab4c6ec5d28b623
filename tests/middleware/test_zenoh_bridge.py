"""The query-reply path of the Zenoh bridge, pinned without timing anything: a reply reaches the
loop as plain bytes with one post (no Zenoh object crosses to the loop), the end of an answered query posts
nothing, and a query nobody answers still ends with `Finished`."""

from __future__ import annotations

import asyncio
import json
import threading
from collections.abc import AsyncIterator, Callable

import pytest
import zenoh

from robovoice.middleware.zenoh_bridge import LoopBridge, U, close_session, undeclare
from robovoice.middleware.zenoh_query import Answer, Exchange, Finished, send_query

BOUND_S = 5.0


class CountingBridge(LoopBridge):
    """A real `LoopBridge` that counts its posts and says when Zenoh ended a query."""

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        super().__init__(loop)
        self.posts = 0
        self.ended = threading.Event()

    def post(self, fn: Callable[..., object], *args: object) -> None:
        self.posts += 1
        super().post(fn, *args)

    def replies(self, convert: Callable[[zenoh.Reply], U], on_reply: Callable[[U], object],
                on_none: Callable[[], object]) -> zenoh.handlers.Callback[zenoh.Reply]:
        inner = super().replies(convert, on_reply, on_none)

        def drop() -> None:  # on Zenoh's thread, after the last reply callback
            if inner.drop is not None:
                inner.drop()
            self.ended.set()

        return zenoh.handlers.Callback(inner.callback, drop, indirect=False)


@pytest.fixture
async def session() -> AsyncIterator[zenoh.Session]:
    config = zenoh.Config()
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("listen/endpoints", json.dumps([]))
    opened = await asyncio.to_thread(zenoh.open, config)
    yield opened
    await asyncio.to_thread(close_session, opened)


async def test_an_answered_query_posts_once_with_plain_bytes(session: zenoh.Session) -> None:
    bridge = CountingBridge(asyncio.get_running_loop())

    def answer(query: zenoh.Query) -> None:
        with query:
            query.reply("test/bridge/echo", query.payload.to_bytes() if query.payload else b"")

    queryable = session.declare_queryable("test/bridge/echo", answer)
    try:
        exchange = Exchange("echo")
        send_query(session, bridge, exchange, "test/bridge/echo", {"x": 1}, timeout=BOUND_S)
        item = await asyncio.wait_for(exchange.next(), BOUND_S)
        assert await asyncio.to_thread(bridge.ended.wait, BOUND_S)  # Zenoh is done with the query
        for _ in range(3):
            await asyncio.sleep(0)  # let the loop run anything the end of the query posted
    finally:
        undeclare(queryable)
    assert item == Answer(True, b'{"x":1}', None) and type(item.payload) is bytes
    assert bridge.posts == 1  # the reply only: the end of an answered query wakes nobody
    assert exchange.pending() == 0


async def test_an_unanswered_query_ends_with_finished(session: zenoh.Session) -> None:
    bridge = CountingBridge(asyncio.get_running_loop())
    exchange = Exchange("nobody")
    send_query(session, bridge, exchange, "test/bridge/nobody", None, timeout=BOUND_S)
    item = await asyncio.wait_for(exchange.next(), BOUND_S + 2)
    assert isinstance(item, Finished) and bridge.posts == 1
