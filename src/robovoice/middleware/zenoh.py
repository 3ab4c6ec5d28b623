"""`zenoh://`: the robot's middleware over Eclipse Zenoh (layout and wire format: docs/zenoh.md).

RPCs are queryables, actions a goal query whose reply is the result (feedback and cancel
are publications keyed by the goal id), topics publications, presence liveliness tokens,
and each node serves its NodeInfo (with its manifest) so a server needs no shared files.
Module map: `zenoh_config` (URIs), `zenoh_keys` (key layout), `zenoh_codec` (payloads),
`zenoh_bridge` (Zenoh threads -> event loop), `zenoh_query` (a query in flight),
`zenoh_presence` (liveliness and infos), `zenoh_node` (serving a node), `zenoh_topic`
(a subscription), this module (the session and the client side).
"""

from __future__ import annotations

import asyncio
import json
import logging
import re
import uuid
from collections.abc import Callable, Mapping

from robovoice.errors import (
    CallTimeoutError,
    ConfigError,
    MiddlewareError,
    MissingDependencyError,
    NodeUnavailableError,
    RobotFailure,
)

try:
    import zenoh
except ImportError as exc:  # pragma: no cover - depends on the install
    raise MissingDependencyError("the Zenoh middleware", "pip install 'robovoice[zenoh]'") from exc

from robovoice.middleware.base import (
    JSON,
    ActionHandler,
    Feedback,
    FeedbackSender,
    Message,
    NodeInfo,
    PresenceEvent,
    RpcHandler,
    RpcKind,
)
from robovoice.middleware.zenoh_bridge import LoopBridge, close_session, undeclare
from robovoice.middleware.zenoh_codec import decode, decode_object, failure_from_bytes, feedback_from_bytes
from robovoice.middleware.zenoh_config import ZenohSettings
from robovoice.middleware.zenoh_keys import KeyLayout
from robovoice.middleware.zenoh_node import ZenohNodeHost
from robovoice.middleware.zenoh_presence import Presence, PresenceWatch
from robovoice.middleware.zenoh_query import Answer, Closed, Exchange, Finished, Item, NodeGone, send_query
from robovoice.middleware.zenoh_topic import TopicSubscription

log = logging.getLogger(__name__)

PRESENCE_SYNC_S = 3.0
"""At start, how long to wait for the nodes already present to tell what they offer."""
MESH_SETTLE_S = 0.05
MESH_SETTLE_MAX_S = 1.0
"""At start in peer mode: how long the peer count must hold still, and the most to wait."""
FEEDBACK_DRAIN_S = 0.5
"""After an action's result, how long to wait for feedback the node sent before it."""
TOPIC_BACKLOG = 1000
"""Messages of one topic that may wait for the event loop; beyond, the oldest are dropped."""


class ZenohMiddleware:
    """A Zenoh session as a robovoice `Middleware` (see the module docstring)."""

    def __init__(self, settings: ZenohSettings) -> None:
        self._settings = settings
        self._layout = KeyLayout(settings.robot)
        self._client_id = uuid.uuid4().hex
        self._session: zenoh.Session | None = None
        self._bridge: LoopBridge | None = None
        self._presence: Presence | None = None
        self._entities: list[zenoh.Subscriber[None] | zenoh.LivelinessToken] = []
        self._hosts: dict[str, ZenohNodeHost] = {}
        self._subscriptions: set[TopicSubscription] = set()
        self._exchanges: dict[str, set[Exchange]] = {}
        self._goals: dict[str, Exchange] = {}

    @classmethod
    def from_uri(cls, uri: str) -> ZenohMiddleware:
        return cls(ZenohSettings.from_uri(uri))

    @property
    def uri(self) -> str:
        return self._settings.uri

    @property
    def layout(self) -> KeyLayout:
        return self._layout

    # --- life cycle ------------------------------------------------------------------------
    async def start(self) -> None:
        if self._session is not None:
            return
        self._bridge = bridge = LoopBridge(asyncio.get_running_loop())
        self._session = session = await self._open()
        try:
            layout = self._layout
            self._entities.append(session.liveliness().declare_token(layout.client(self._client_id)))
            self._entities.append(session.declare_subscriber(layout.feedback_all(),
                                                             bridge.handler(self._on_feedback)))
            self._presence = Presence(session, layout, bridge, self._on_node_left)
            self._presence.start()
            if self._settings.mode == "peer":
                await _settle(session)
            await self._presence.sync(PRESENCE_SYNC_S)
        except BaseException:
            await self.close()
            raise
        log.info("zenoh middleware up (%s, robot %r, %d nodes present)", self._settings.describe(),
                 self._settings.robot, len(self._presence.nodes()))

    async def _open(self) -> zenoh.Session:
        settings = self._settings
        try:
            config = zenoh.Config.from_file(settings.config_file) if settings.config_file else zenoh.Config()
            for key, value in settings.json5_entries().items():
                config.insert_json5(key, json.dumps(value))
        except (zenoh.ZError, OSError, ValueError) as exc:
            raise ConfigError(f"{settings.uri}: bad Zenoh configuration: {_brief(exc)}") from exc
        opening = asyncio.get_running_loop().run_in_executor(None, zenoh.open, config)
        try:
            async with asyncio.timeout(settings.timeout_s + 5.0):
                return await asyncio.shield(opening)
        except zenoh.ZError as exc:
            raise MiddlewareError(f"cannot reach the Zenoh network ({settings.describe()}): {_brief(exc)}") from exc
        except TimeoutError:
            opening.add_done_callback(_close_late_session)
            raise MiddlewareError(f"opening the Zenoh session took too long ({settings.describe()})") from None
        except asyncio.CancelledError:
            opening.add_done_callback(_close_late_session)
            raise

    async def close(self) -> None:
        session = self._session
        if session is None:
            return
        for host in list(self._hosts.values()):
            await host.leave()
        self._hosts.clear()
        for exchanges in list(self._exchanges.values()):
            for exchange in exchanges:
                exchange.push(Closed())
        for subscription in list(self._subscriptions):
            subscription.close()
        if self._presence is not None:
            await self._presence.close()
            self._presence = None
        for entity in self._entities:
            undeclare(entity)
        self._entities.clear()
        self._session = None
        await asyncio.to_thread(close_session, session)
        log.info("zenoh middleware closed")

    def _open_session(self) -> tuple[zenoh.Session, LoopBridge]:
        if self._session is None or self._bridge is None:
            raise MiddlewareError(f"the Zenoh middleware {self.uri} is not started (or closed)")
        return self._session, self._bridge

    # --- node side -------------------------------------------------------------------------
    async def host(self, info: NodeInfo, rpcs: Mapping[str, RpcHandler],
                   actions: Mapping[str, ActionHandler]) -> ZenohNodeHost:
        session, bridge = self._open_session()
        old = self._hosts.pop(info.name, None)
        if old is not None:
            await old.leave()
        host = ZenohNodeHost(session, self._layout, bridge, info, rpcs, actions)
        host.declare()
        self._hosts[info.name] = host
        return host

    # --- client side -----------------------------------------------------------------------
    def _begin(self, node: str, goal_id: str | None = None) -> Exchange:
        exchange = Exchange(node, goal_id)
        self._exchanges.setdefault(node, set()).add(exchange)
        if goal_id is not None:
            self._goals[goal_id] = exchange
        return exchange

    def _end(self, exchange: Exchange) -> None:
        exchanges = self._exchanges.get(exchange.node)
        if exchanges is not None:
            exchanges.discard(exchange)
            if not exchanges:
                del self._exchanges[exchange.node]
        if exchange.goal_id is not None:
            self._goals.pop(exchange.goal_id, None)

    def _on_node_left(self, node: str) -> None:
        for exchange in self._exchanges.get(node, ()):
            exchange.push(NodeGone())

    def _on_feedback(self, sample: zenoh.Sample) -> None:
        goal = self._layout.parse_goal(str(sample.key_expr), "feedback")
        exchange = None if goal is None else self._goals.get(goal.goal_id)
        if exchange is None:
            return
        try:
            exchange.push(feedback_from_bytes(sample.payload.to_bytes()))
        except ValueError as exc:
            log.warning("dropped bad feedback on %s: %s", sample.key_expr, exc)

    def _send(self, exchange: Exchange, key: str, args: Mapping[str, JSON], timeout: float,
              parameters: dict[str, str]) -> None:
        session, bridge = self._open_session()
        try:
            send_query(session, bridge, exchange, key, args, timeout=timeout, parameters=parameters)
        except zenoh.ZError as exc:
            raise MiddlewareError(f"cannot send {key} on {self.uri}: {_brief(exc)}") from exc

    async def call(self, node: str, rpc: str, args: Mapping[str, JSON], *, timeout: float) -> JSON:
        self._open_session()
        exchange = self._begin(node)
        try:
            self._send(exchange, self._layout.rpc(node, rpc), args, timeout, {"timeout": f"{timeout:g}"})
            try:
                item = await exchange.next(timeout)
            except TimeoutError:
                raise self._timed_out(node, rpc, timeout) from None
        finally:
            self._end(exchange)
        return self._outcome(item, node, rpc, "rpc")

    async def run_action(self, node: str, action: str, args: Mapping[str, JSON], *,
                         on_feedback: FeedbackSender, timeout: float) -> JSON:
        self._open_session()
        goal_id = uuid.uuid4().hex
        exchange = self._begin(node, goal_id)
        ended = False
        try:
            self._send(exchange, self._layout.goal(node, action, goal_id), args, timeout,
                       {"timeout": f"{timeout:g}", "client": self._client_id})
            try:
                async with asyncio.timeout(timeout):
                    item, received = await self._follow(exchange, on_feedback)
            except TimeoutError:
                raise self._timed_out(node, action, timeout) from None
            ended = True
            await self._drain(exchange, on_feedback, item, received)
        finally:
            self._end(exchange)
            if not ended:  # timed out, cancelled, or on_feedback failed: stop the goal on the node
                self._send_cancel(node, action, goal_id)
        return self._outcome(item, node, action, "action")

    async def _follow(self, exchange: Exchange, on_feedback: FeedbackSender) -> tuple[Item, int]:
        """Pass feedback on until the goal ends: the item it ended with, the feedback count."""
        received = 0
        while True:
            item = await exchange.next()
            if not isinstance(item, Feedback):
                return item, received
            received += 1
            await on_feedback(item)

    async def _drain(self, exchange: Exchange, on_feedback: FeedbackSender, item: Item, received: int) -> None:
        """After a result, pass on the feedback the node says it sent before it (briefly)."""
        if not (isinstance(item, Answer) and item.ok):
            return
        sent = decode_object(item.attachment).get("feedback")
        if not isinstance(sent, int):
            return
        try:
            async with asyncio.timeout(FEEDBACK_DRAIN_S):
                while received < sent:
                    late = await exchange.next()
                    if isinstance(late, Feedback):
                        received += 1
                        await on_feedback(late)
        except TimeoutError:
            log.debug("goal %s: %s of %s feedback messages arrived", exchange.goal_id, received, sent)

    def _send_cancel(self, node: str, action: str, goal_id: str) -> None:
        session = self._session
        if session is None:
            return
        try:
            session.put(self._layout.cancel(node, action, goal_id), b"")
        except zenoh.ZError as exc:
            log.warning("could not cancel goal %s of %s.%s: %s", goal_id, node, action, exc)

    def _timed_out(self, node: str, rpc: str, timeout: float) -> CallTimeoutError:
        return CallTimeoutError(
            f"{node}.{rpc} did not answer within {timeout:g} s",
            hint="the robot may be busy; try again or tell the user",
            details={"node": node, "rpc": rpc, "timeout_s": timeout},
        )

    def _outcome(self, item: Item, node: str, rpc: str, kind: RpcKind) -> JSON:
        """The result the query ended with, or the failure it stands for."""
        where = f"{node}.{rpc}"
        if isinstance(item, Answer) and item.ok:
            try:
                return decode(item.payload)
            except ValueError as exc:
                raise RobotFailure(f"{where} answered with invalid JSON: {exc}", code="internal_error",
                                   details={"node": node, "rpc": rpc}) from None
        if isinstance(item, Answer):
            raise failure_from_bytes(item.payload, where)
        if isinstance(item, Closed):
            raise MiddlewareError(f"the Zenoh middleware {self.uri} was closed during {where}")
        present = self.nodes()
        if isinstance(item, NodeGone):
            raise NodeUnavailableError(f"node {node!r} left while {rpc} was running",
                                       hint="the robot part went offline; tell the user",
                                       details={"node": node, "rpc": rpc})
        assert isinstance(item, Finished)
        info = present.get(node)
        if info is None:
            raise NodeUnavailableError(
                f"node {node!r} is not running",
                hint="the robot part that offers this is offline; try again later or tell the user",
                details={"node": node, "present": sorted(present)},
            )
        offered = info.rpc(rpc)
        if offered is None or offered.kind != kind:
            raise RobotFailure(f"node {node!r} has no {'action' if kind == 'action' else 'RPC'} {rpc!r}",
                               code="unknown_rpc", details={"node": node, "rpc": rpc})
        raise NodeUnavailableError(f"node {node!r} did not answer {rpc}",
                                   hint="the robot part may be restarting; try again or tell the user",
                                   details={"node": node, "rpc": rpc})

    async def subscribe(self, topic: str, callback: Callable[[Message], None]) -> TopicSubscription:
        session, bridge = self._open_session()
        subscription = TopicSubscription(self._subscriptions, topic, callback)
        handler = bridge.stream(subscription.deliver, limit=TOPIC_BACKLOG, what=f"topic {topic!r}")
        subscription._subscriber = session.declare_subscriber(self._layout.topic(topic), handler)
        self._subscriptions.add(subscription)
        return subscription

    def nodes(self) -> Mapping[str, NodeInfo]:
        return {} if self._presence is None else self._presence.nodes()

    async def watch(self, callback: Callable[[PresenceEvent], None]) -> PresenceWatch:
        self._open_session()
        assert self._presence is not None
        return self._presence.watch(callback)


async def _settle(session: zenoh.Session) -> None:
    """Let the peer mesh form: peers learnt from the ones we connected to (gossip) connect
    within milliseconds of opening; wait until the number of peers holds still for a moment,
    so the presence sync sees the nodes already running."""
    loop = asyncio.get_running_loop()
    last, since = -1, loop.time()
    try:
        async with asyncio.timeout(MESH_SETTLE_MAX_S):
            while True:
                count, now = len(session.info.peers_zid()), loop.time()
                if count != last:
                    last, since = count, now
                elif now - since >= MESH_SETTLE_S:
                    return
                await asyncio.sleep(0.01)
    except TimeoutError:
        log.debug("the peer mesh was still changing after %g s", MESH_SETTLE_MAX_S)


def _brief(exc: BaseException) -> str:
    """A Zenoh error message without its Rust source locations."""
    return re.sub(r"\s+at /\S+\.rs:\d+\.?", "", str(exc)).strip()


def _close_late_session(opening: asyncio.Future[zenoh.Session]) -> None:
    if not opening.cancelled() and opening.exception() is None:
        close_session(opening.result())
