"""Who is there: node presence from liveliness tokens, node infos from their queryables.

A liveliness subscriber on ``robovoice/<robot>/alive/*`` (with history, so tokens already
present are reported too) tells when a node appears or disappears. When one appears, its
``.../node/<node>/info`` queryable is asked for the NodeInfo (a few tries); only then is
`NodeJoined` fired. When the token disappears (the node left, its process died, its link
broke) `NodeLeft` is fired and the adapter fails the calls still waiting on that node.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable, Mapping

import zenoh

from robovoice.middleware.base import NodeInfo, NodeJoined, NodeLeft, PresenceEvent
from robovoice.middleware.zenoh_bridge import LoopBridge, undeclare
from robovoice.middleware.zenoh_codec import decode, failure_from_bytes, info_from_json
from robovoice.middleware.zenoh_keys import KeyLayout
from robovoice.middleware.zenoh_query import Answer, Exchange, send_query

log = logging.getLogger(__name__)

INFO_TIMEOUTS_S = (1.0, 2.0, 4.0)
"""How long each try to fetch a node's info waits."""
INFO_RETRY_PAUSE_S = 0.1


class PresenceWatch:
    """A `watch()` handle."""

    def __init__(self, watchers: dict[int, Callable[[PresenceEvent], None]], key: int) -> None:
        self._watchers = watchers
        self._key = key

    def close(self) -> None:
        self._watchers.pop(self._key, None)


class Presence:
    """The nodes of one robot, as a client sees them (see the module docstring)."""

    def __init__(self, session: zenoh.Session, layout: KeyLayout, bridge: LoopBridge,
                 on_left: Callable[[str], None]) -> None:
        self._session = session
        self._layout = layout
        self._bridge = bridge
        self._on_left = on_left
        self._nodes: dict[str, NodeInfo] = {}
        self._fetching: dict[str, asyncio.Task[None]] = {}
        self._watchers: dict[int, Callable[[PresenceEvent], None]] = {}
        self._next_watcher = 0
        self._subscriber: zenoh.Subscriber[None] | None = None

    def start(self) -> None:
        self._subscriber = self._session.liveliness().declare_subscriber(
            self._layout.alive_all(), self._bridge.handler(self._on_token), history=True)

    async def sync(self, timeout: float) -> None:
        """Ask who is there now and wait (at most `timeout`) until their infos are in."""
        done = asyncio.Event()
        names: list[str] = []

        def on_reply(reply: zenoh.Reply) -> None:
            if reply.ok is not None:
                names.append(self._layout.last_chunk(str(reply.ok.key_expr)))

        self._session.liveliness().get(self._layout.alive_all(), self._bridge.handler(on_reply, done.set),
                                       timeout=timeout)
        try:
            async with asyncio.timeout(timeout):
                await done.wait()
                for name in names:
                    self._ensure_fetch(name)
                pending = [task for name, task in self._fetching.items() if name in names]
                if pending:
                    await asyncio.wait(pending)
        except TimeoutError:
            log.warning("presence: the nodes present at start did not all answer within %g s", timeout)

    def nodes(self) -> Mapping[str, NodeInfo]:
        return dict(self._nodes)

    def watch(self, callback: Callable[[PresenceEvent], None]) -> PresenceWatch:
        for info in list(self._nodes.values()):
            callback(NodeJoined(info))
        self._next_watcher += 1
        self._watchers[self._next_watcher] = callback
        return PresenceWatch(self._watchers, self._next_watcher)

    def _fire(self, event: PresenceEvent) -> None:
        for callback in list(self._watchers.values()):
            try:
                callback(event)
            except Exception:  # a watcher's bug must not break presence
                log.exception("presence callback failed")

    # --- liveliness ------------------------------------------------------------------------
    def _on_token(self, sample: zenoh.Sample) -> None:
        name = self._layout.last_chunk(str(sample.key_expr))
        if sample.kind == zenoh.SampleKind.PUT:
            self._ensure_fetch(name)
            return
        fetch = self._fetching.pop(name, None)
        if fetch is not None:
            fetch.cancel()
        if self._nodes.pop(name, None) is not None:
            log.info("node %s left", name)
            self._on_left(name)
            self._fire(NodeLeft(name))

    def _ensure_fetch(self, name: str) -> None:
        if name in self._nodes or name in self._fetching:
            return
        task = asyncio.create_task(self._fetch(name), name=f"zenoh-info-{name}")
        self._fetching[name] = task
        task.add_done_callback(self._fetched)

    def _fetched(self, task: asyncio.Task[None]) -> None:
        if not task.cancelled() and task.exception() is not None:  # _fetch catches what it expects
            log.error("fetching a node's info failed", exc_info=task.exception())

    async def _fetch(self, name: str) -> None:
        info = NodeInfo(name)
        for attempt, timeout in enumerate(INFO_TIMEOUTS_S, 1):
            answer = await self._ask_info(name, timeout)
            if answer is not None and answer.ok:
                try:
                    info = info_from_json(decode(answer.payload), name)
                except ValueError as exc:
                    log.error("node %s: its info on %s is invalid (%s); it offers nothing",
                              name, self._layout.info(name), exc)
                break
            if answer is not None:
                failure = failure_from_bytes(answer.payload, self._layout.info(name))
                log.error("node %s: its info query failed: %s", name, failure.message)
                break
            log.debug("node %s: no info yet (try %d)", name, attempt)
            await asyncio.sleep(INFO_RETRY_PAUSE_S * attempt)  # not declared yet: give it a moment
        else:
            log.warning("node %s: no answer on %s; it offers nothing", name, self._layout.info(name))
        if self._fetching.get(name) is asyncio.current_task():
            del self._fetching[name]
        self._nodes[name] = info
        log.info("node %s joined (%d RPCs, %d topics)", name, len(info.rpcs), len(info.topics))
        self._fire(NodeJoined(info))

    async def _ask_info(self, name: str, timeout: float) -> Answer | None:
        exchange = Exchange(name)
        send_query(self._session, self._bridge, exchange, self._layout.info(name), None, timeout=timeout)
        try:
            async with asyncio.timeout(timeout):
                item = await exchange.next()
        except TimeoutError:
            return None
        return item if isinstance(item, Answer) else None  # finished with no answer: not declared yet

    async def close(self) -> None:
        fetches = list(self._fetching.values())
        for task in fetches:
            task.cancel()
        if fetches:
            await asyncio.wait(fetches)
        self._fetching.clear()
        self._watchers.clear()
        if self._subscriber is not None:
            undeclare(self._subscriber)
            self._subscriber = None
