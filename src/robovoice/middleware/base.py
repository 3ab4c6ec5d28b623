"""The middleware seam: what robovoice needs from a robot middleware.

A middleware carries four things between *nodes* (the robot's processes) and
*clients* (the MCP server, the snapshot buffers):

- RPCs: call a named function of a node with JSON-like arguments, with a timeout;
- actions: long-running calls with feedback, a result, and cancellation;
- topics: publish / subscribe of JSON-like messages (latest value semantics are the
  snapshot node's business, not the middleware's);
- presence: nodes join (announcing their RPCs, topics and manifest) and leave.

Adapters are chosen by URI (`memory://`, `zenoh://...`; see `robovoice.middleware.open_middleware`).
Every callback an adapter invokes runs on the event loop of the task that created the
adapter: adapters whose transport uses threads bridge into asyncio themselves.

Values crossing the middleware are JSON-like (dict, list, str, int, float, bool, None).
Binary data such as camera images travels as ``{"mime_type": "image/jpeg", "data": <base64>}``
so that nodes written in any language can speak it.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal, Protocol, runtime_checkable

JSON = Any
"""A JSON-like value: dict, list, str, int, float, bool or None."""

RpcKind = Literal["rpc", "action"]


@dataclass(frozen=True, slots=True)
class RpcInfo:
    """One callable a node offers: its name, kind and parameter names."""

    name: str
    kind: RpcKind = "rpc"
    params: tuple[str, ...] = ()
    description: str = ""


@dataclass(frozen=True, slots=True)
class NodeInfo:
    """What a node announces when it joins.

    `manifest` is the raw JSON of the node's ``mcp.json`` (validated by the MCP server,
    not here), `manifest_source` says where it came from, for error messages.
    """

    name: str
    rpcs: tuple[RpcInfo, ...] = ()
    topics: tuple[str, ...] = ()
    manifest: Mapping[str, JSON] | None = None
    manifest_source: str = ""

    def rpc(self, name: str) -> RpcInfo | None:
        return next((r for r in self.rpcs if r.name == name), None)


@dataclass(frozen=True, slots=True)
class Message:
    """One message on a topic. `stamp` is the publisher's wall clock (UNIX seconds)."""

    topic: str
    value: JSON
    stamp: float


@dataclass(frozen=True, slots=True)
class Feedback:
    """Progress of a running action. `progress`/`total` follow MCP progress notifications."""

    progress: float
    total: float | None = None
    message: str = ""
    data: Mapping[str, JSON] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class NodeJoined:
    node: NodeInfo


@dataclass(frozen=True, slots=True)
class NodeLeft:
    name: str


PresenceEvent = NodeJoined | NodeLeft

FeedbackSender = Callable[[Feedback], Awaitable[None]]
RpcHandler = Callable[[dict[str, JSON]], Awaitable[JSON]]
ActionHandler = Callable[[dict[str, JSON], FeedbackSender], Awaitable[JSON]]


class Subscription(Protocol):
    """A handle on a subscription or a presence watch; `close()` ends it."""

    def close(self) -> None: ...


class NodeHost(Protocol):
    """A node hosted on a middleware: publish on topics, leave."""

    @property
    def info(self) -> NodeInfo: ...

    def publish(self, topic: str, value: JSON, stamp: float | None = None) -> None:
        """Publish a message; `stamp` defaults to now. Never blocks."""
        ...

    async def leave(self) -> None:
        """Withdraw the node: its RPCs disappear, in-flight calls fail with `node_unavailable`."""
        ...


@runtime_checkable
class Middleware(Protocol):
    """A robot middleware as robovoice sees it (see the module docstring)."""

    @property
    def uri(self) -> str: ...

    async def start(self) -> None:
        """Connect. Raises `MiddlewareError` naming the endpoint when it cannot."""
        ...

    async def close(self) -> None: ...

    # --- node side ---------------------------------------------------------------
    async def host(
        self,
        info: NodeInfo,
        rpcs: Mapping[str, RpcHandler],
        actions: Mapping[str, ActionHandler],
    ) -> NodeHost:
        """Serve a node's RPCs and actions and announce it (with its manifest)."""
        ...

    # --- client side -------------------------------------------------------------
    async def call(self, node: str, rpc: str, args: Mapping[str, JSON], *, timeout: float) -> JSON:
        """Call an RPC. Raises `RobotFailure` (its subclasses `NodeUnavailableError`,
        `CallTimeoutError`, or whatever the node raised); never returns None for failure."""
        ...

    async def run_action(
        self,
        node: str,
        action: str,
        args: Mapping[str, JSON],
        *,
        on_feedback: FeedbackSender,
        timeout: float,
    ) -> JSON:
        """Run a long action to its result. Cancelling the awaiting task cancels the
        action on the node. Raises like `call`."""
        ...

    async def subscribe(self, topic: str, callback: Callable[[Message], None]) -> Subscription:
        """Receive the messages published on `topic` (exact name) on the event loop.

        A networked adapter may drop the oldest queued messages (and log it) when the event
        loop falls far behind a fast topic, so memory stays bounded; subscribers that keep
        only the latest value (snapshots) are unaffected."""
        ...

    def nodes(self) -> Mapping[str, NodeInfo]:
        """The nodes present now."""
        ...

    async def watch(self, callback: Callable[[PresenceEvent], None]) -> Subscription:
        """Be told when nodes join or leave. Nodes already present are reported as joined."""
        ...
