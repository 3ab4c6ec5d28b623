"""`memory://`: the in-process middleware, the embedded default.

Everything runs on one event loop. RPC arguments and results are copied through JSON so
that code tested here behaves as it will over a network (no shared mutable objects, no
values that cannot be serialised).
"""

from __future__ import annotations

import asyncio
import json
import logging
import time
from collections.abc import Awaitable, Callable, Mapping
from dataclasses import dataclass, field

from robovoice.errors import CallTimeoutError, NodeUnavailableError, RobotFailure
from robovoice.middleware.base import (
    JSON,
    ActionHandler,
    FeedbackSender,
    Message,
    NodeInfo,
    NodeJoined,
    NodeLeft,
    PresenceEvent,
    RpcHandler,
)

log = logging.getLogger(__name__)


def _copy(value: JSON) -> JSON:
    return json.loads(json.dumps(value))


class _Callbacks:
    """A set of callbacks with close handles."""

    def __init__(self) -> None:
        self._items: dict[int, Callable[..., None]] = {}
        self._next = 0

    def add(self, callback: Callable[..., None]) -> _Handle:
        self._next += 1
        self._items[self._next] = callback
        return _Handle(self._items, self._next)

    def fire(self, *args: object) -> None:
        for callback in list(self._items.values()):
            try:
                callback(*args)
            except Exception:  # a subscriber's bug must not break the publisher
                log.exception("subscriber callback failed")


@dataclass
class _Handle:
    items: dict[int, Callable[..., None]]
    key: int

    def close(self) -> None:
        self.items.pop(self.key, None)


@dataclass
class _HostedNode:
    bus: MemoryMiddleware
    info: NodeInfo
    rpcs: Mapping[str, RpcHandler]
    actions: Mapping[str, ActionHandler]
    in_flight: set[asyncio.Task[JSON]] = field(default_factory=set)
    present: bool = True

    def publish(self, topic: str, value: JSON, stamp: float | None = None) -> None:
        self.bus._deliver(Message(topic, value, time.time() if stamp is None else stamp))

    async def leave(self) -> None:
        if not self.present:
            return
        self.present = False
        self.bus._remove(self)
        for task in list(self.in_flight):
            task.cancel()


class MemoryMiddleware:
    """The in-process bus. One instance is one robot."""

    def __init__(self, uri: str = "memory://") -> None:
        self._uri = uri
        self._nodes: dict[str, _HostedNode] = {}
        self._topics: dict[str, _Callbacks] = {}
        self._presence = _Callbacks()

    @property
    def uri(self) -> str:
        return self._uri

    async def start(self) -> None:
        return None

    async def close(self) -> None:
        for node in list(self._nodes.values()):
            await node.leave()

    # --- node side -------------------------------------------------------------------
    async def host(
        self,
        info: NodeInfo,
        rpcs: Mapping[str, RpcHandler],
        actions: Mapping[str, ActionHandler],
    ) -> _HostedNode:
        if info.name in self._nodes:
            await self._nodes[info.name].leave()
        node = _HostedNode(self, info, dict(rpcs), dict(actions))
        self._nodes[info.name] = node
        self._presence.fire(NodeJoined(info))
        return node

    def _remove(self, node: _HostedNode) -> None:
        if self._nodes.get(node.info.name) is node:
            del self._nodes[node.info.name]
            self._presence.fire(NodeLeft(node.info.name))

    def _deliver(self, message: Message) -> None:
        callbacks = self._topics.get(message.topic)
        if callbacks is not None:
            callbacks.fire(message)

    # --- client side -----------------------------------------------------------------
    def _node(self, name: str) -> _HostedNode:
        node = self._nodes.get(name)
        if node is None:
            raise NodeUnavailableError(
                f"node {name!r} is not running",
                hint="the robot part that offers this is offline; try again later or tell the user",
                details={"node": name, "present": sorted(self._nodes)},
            )
        return node

    async def call(self, node: str, rpc: str, args: Mapping[str, JSON], *, timeout: float) -> JSON:
        hosted = self._node(node)
        handler = hosted.rpcs.get(rpc)
        if handler is None:
            raise RobotFailure(f"node {node!r} has no RPC {rpc!r}", code="unknown_rpc",
                               details={"node": node, "rpc": rpc})
        return await self._run(hosted, rpc, handler(_copy(dict(args))), timeout)

    async def run_action(
        self,
        node: str,
        action: str,
        args: Mapping[str, JSON],
        *,
        on_feedback: FeedbackSender,
        timeout: float,
    ) -> JSON:
        hosted = self._node(node)
        handler = hosted.actions.get(action)
        if handler is None:
            raise RobotFailure(f"node {node!r} has no action {action!r}", code="unknown_rpc",
                               details={"node": node, "action": action})
        return await self._run(hosted, action, handler(_copy(dict(args)), on_feedback), timeout)

    async def _run(self, hosted: _HostedNode, name: str, work: Awaitable[JSON], timeout: float) -> JSON:
        task: asyncio.Task[JSON] = asyncio.ensure_future(work)
        hosted.in_flight.add(task)
        try:
            async with asyncio.timeout(timeout):
                result = await asyncio.shield(task)
        except TimeoutError:
            task.cancel()
            raise CallTimeoutError(
                f"{hosted.info.name}.{name} did not answer within {timeout:g} s",
                hint="the robot may be busy; try again or tell the user",
                details={"node": hosted.info.name, "rpc": name, "timeout_s": timeout},
            ) from None
        except asyncio.CancelledError:
            if task.cancelled() and not hosted.present:
                raise NodeUnavailableError(
                    f"node {hosted.info.name!r} left while {name} was running",
                    hint="the robot part went offline; tell the user",
                    details={"node": hosted.info.name, "rpc": name},
                ) from None
            task.cancel()  # our caller was cancelled: cancel the work on the node too
            raise
        except RobotFailure:
            raise
        except Exception as exc:  # a node's bug becomes a tool error, not a server crash
            log.exception("%s.%s failed", hosted.info.name, name)
            raise RobotFailure(f"{hosted.info.name}.{name} failed: {exc}", code="internal_error",
                               details={"node": hosted.info.name, "rpc": name}) from exc
        finally:
            hosted.in_flight.discard(task)
        return _copy(result)

    async def subscribe(self, topic: str, callback: Callable[[Message], None]) -> _Handle:
        return self._topics.setdefault(topic, _Callbacks()).add(callback)

    def nodes(self) -> Mapping[str, NodeInfo]:
        return {name: node.info for name, node in self._nodes.items()}

    async def watch(self, callback: Callable[[PresenceEvent], None]) -> _Handle:
        for node in list(self._nodes.values()):
            callback(NodeJoined(node.info))
        return self._presence.add(callback)
