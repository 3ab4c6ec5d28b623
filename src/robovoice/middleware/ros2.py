"""`ros2://`: a robot that runs ROS 2, reached through rclpy (docs/ros2.md).

The robot's nodes know nothing of robovoice: a folder of manifests (``manifests=DIR`` in the
URI) binds tools to the ROS 2 services and actions they already offer and snapshots to their
topics. Each manifest is one robovoice *node*; it is present while every service, action
server and topic publisher it names is in the ROS graph (`ros2_presence`), and it announces
itself with the manifest the MCP server uses, its input schemas derived from the ROS types
(`ros2_bindings`). Module map: `ros2_config` (URIs), `ros2_types` (JSON ⇄ messages, schemas),
`ros2_bindings` (manifests → bindings), `ros2_schema` (input schemas), `ros2_bridge` (the rclpy thread → event loop),
`ros2_presence` (the graph), `ros2_calls` (services and actions), this module.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping
from typing import Any

from robovoice.errors import ConfigError, MissingDependencyError, NodeUnavailableError, RobotFailure

try:
    import rclpy  # noqa: F401  # the guarded import: the rest of the ros2_* modules need it
except ImportError as exc:  # pragma: no cover - depends on the install
    raise MissingDependencyError("the ROS 2 middleware", "pip install 'robovoice[ros2]'") from exc

import asyncio

from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

from robovoice.manifest import format_error, load_manifest_dir
from robovoice.manifest.errors import ManifestErrors
from robovoice.middleware.base import (
    JSON,
    ActionHandler,
    FeedbackSender,
    Message,
    NodeHost,
    NodeInfo,
    PresenceEvent,
    RpcHandler,
    RpcKind,
)
from robovoice.middleware.ros2_bindings import NodeBinding, compile_manifest
from robovoice.middleware.ros2_bridge import RosBridge
from robovoice.middleware.ros2_calls import Ros2Calls
from robovoice.middleware.ros2_config import Ros2Settings
from robovoice.middleware.ros2_host import ANNOUNCE_TOPIC, Ros2NodeHost, info_from_json
from robovoice.middleware.ros2_presence import GraphPresence, PresenceWatch
from robovoice.middleware.ros2_topics import TopicSubscription, subscribe_topic

log = logging.getLogger(__name__)

DISCOVERY_S = 3.0
"""At start, how long to wait for the manifests' nodes already running to be discovered."""


def load_bindings(settings: Ros2Settings) -> dict[str, NodeBinding]:
    """Compile the manifest folder of `settings`; bad files are logged (their nodes expose
    nothing), and a folder with no good manifest at all is a `ConfigError` listing why."""
    if settings.manifests is None:
        return {}
    loaded = load_manifest_dir(settings.manifests)
    errors = list(loaded.errors)
    bindings: dict[str, NodeBinding] = {}
    for node, manifest in loaded.manifests.items():
        try:
            bindings[node] = compile_manifest(manifest)
        except ManifestErrors as exc:
            errors.extend(exc.errors)
    if errors and not bindings:
        raise ConfigError("; ".join(format_error(e) for e in errors))
    for error in errors:
        log.warning("manifest not used: %s", format_error(error))
    return bindings


class Ros2Middleware:
    """The `Middleware` over rclpy (see the module docstring)."""

    def __init__(self, settings: Ros2Settings) -> None:
        self._settings = settings
        self._bindings = load_bindings(settings)
        self._bridge: RosBridge | None = None
        self._presence: GraphPresence | None = None
        self._calls: Ros2Calls | None = None
        self._hosts: list[Ros2NodeHost] = []

    @classmethod
    def from_uri(cls, uri: str) -> Ros2Middleware:
        return cls(Ros2Settings.from_uri(uri))

    @property
    def uri(self) -> str:
        return self._settings.uri

    @property
    def bindings(self) -> Mapping[str, NodeBinding]:
        return self._bindings

    async def start(self) -> None:
        if self._bridge is not None:
            return
        loop = asyncio.get_running_loop()
        self._bridge = await asyncio.to_thread(RosBridge, self._settings, loop)
        self._presence = GraphPresence(self._bridge, self._bindings)
        self._presence.start()
        self._calls = Ros2Calls(self._bridge, self._presence)
        self._announcements = self._listen(self._bridge, self._presence)
        await self._discover(self._presence)

    def _listen(self, bridge: RosBridge, presence: GraphPresence) -> Any:
        """Hosted robovoice nodes' announcements (latched): each one a node that may join."""
        from std_msgs.msg import String

        def heard(msg: Any) -> None:  # on the executor thread
            try:
                info = info_from_json(msg.data)
            except (ValueError, KeyError, TypeError):
                log.warning("a malformed announcement on %s", ANNOUNCE_TOPIC)
                return
            bridge.post(presence.announce, info)

        qos = QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL, reliability=ReliabilityPolicy.RELIABLE)
        return bridge.node.create_subscription(String, ANNOUNCE_TOPIC, heard, qos, callback_group=bridge.group)

    async def _discover(self, presence: GraphPresence) -> None:
        """Give DDS discovery a moment (typically 0.1 s, at worst seconds) to find the nodes
        already running, so that a one-shot command sees them; later ones arrive by presence."""
        try:
            async with asyncio.timeout(DISCOVERY_S):
                while len(presence.nodes()) < len(self._bindings):
                    await presence.changed()
        except TimeoutError:
            missing = sorted(set(self._bindings) - set(presence.nodes()))
            log.info("not in the ROS graph yet (their tools come when they do): %s", ", ".join(missing))

    async def close(self) -> None:
        hosts, self._hosts = self._hosts, []
        for host in hosts:
            await host.leave()
        bridge, self._bridge = self._bridge, None
        if self._presence is not None:
            await self._presence.stop()
            self._presence = None
        if self._calls is not None:
            self._calls.close()
            self._calls = None
        if bridge is not None:
            await asyncio.to_thread(bridge.close)

    def _running(self) -> tuple[RosBridge, GraphPresence, Ros2Calls]:
        if self._bridge is None or self._presence is None or self._calls is None:
            raise ConfigError(f"{self.uri}: the middleware is not started")
        return self._bridge, self._presence, self._calls

    # --- node side ------------------------------------------------------------------------
    async def host(self, info: NodeInfo, rpcs: Mapping[str, RpcHandler],
                   actions: Mapping[str, ActionHandler]) -> NodeHost:
        """Serve a robovoice node (the sim's) as a ROS 2 node with JSON interfaces (`ros2_host`)."""
        bridge, _, _ = self._running()
        host = Ros2NodeHost(bridge, info, rpcs, actions)
        self._hosts.append(host)
        return host

    # --- client side ----------------------------------------------------------------------
    def _hosted(self, node: str, rpc: str, kind: RpcKind) -> None:
        info = self.nodes().get(node)
        if info is None:
            raise NodeUnavailableError(f"node {node!r} is not available", hint="the robot part is offline; tell "
                                       "the user", details={"node": node, "rpc": rpc})
        found = info.rpc(rpc)
        if found is None or found.kind != kind:
            what = "RPC" if kind == "rpc" else "action"
            raise RobotFailure(f"node {node!r} has no {what} {rpc!r}", code="unknown_rpc",
                               hint="this is a fault in the robot's manifests; tell the user",
                               details={"node": node, "rpc": rpc})

    def _binding(self, node: str, rpc: str) -> Any:
        _, presence, _ = self._running()
        found = self._bindings.get(node)
        binding = found.tools.get(rpc) if found is not None else None
        if binding is None or not presence.is_present(node):
            raise NodeUnavailableError(
                f"node {node!r} is not available", hint="the robot part is offline; tell the user",
                details={"node": node, "rpc": rpc})
        return binding

    async def call(self, node: str, rpc: str, args: Mapping[str, JSON], *, timeout: float) -> JSON:
        _, presence, calls = self._running()
        if presence.is_hosted(node):
            self._hosted(node, rpc, "rpc")
            return await calls.call_json(node, rpc, args, timeout=timeout)
        binding = self._binding(node, rpc)
        return await self._running()[2].call(node, binding, args, timeout=timeout)

    async def run_action(self, node: str, action: str, args: Mapping[str, JSON], *,
                         on_feedback: FeedbackSender, timeout: float) -> JSON:
        _, presence, calls = self._running()
        if presence.is_hosted(node):
            self._hosted(node, action, "action")
            return await calls.run_json(node, action, args, on_feedback=on_feedback, timeout=timeout)
        binding = self._binding(node, action)
        return await self._running()[2].run_action(node, binding, args, on_feedback=on_feedback,
                                                   timeout=timeout)

    async def subscribe(self, topic: str, callback: Callable[[Message], None]) -> TopicSubscription:
        bridge, _, _ = self._running()
        snapshot = next((n.snapshots[topic] for n in self._bindings.values() if topic in n.snapshots), None)
        return subscribe_topic(bridge, topic, snapshot, callback)

    def graph_actions(self) -> list[tuple[str, list[str]]]:
        """The action servers in the ROS graph now, with their types (as `ros2 action list -t`)."""
        from rclpy.action.graph import get_action_names_and_types

        bridge, _, _ = self._running()
        return [(name, list(types)) for name, types in get_action_names_and_types(bridge.node)]

    def nodes(self) -> Mapping[str, NodeInfo]:
        if self._presence is None:
            return {}
        return self._presence.nodes()

    async def watch(self, callback: Callable[[PresenceEvent], None]) -> PresenceWatch:
        return self._running()[1].watch(callback)
