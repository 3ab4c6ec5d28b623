"""Presence from the ROS 2 graph: a manifest's node is present while every service server,
action server and topic publisher it names is in the graph.

rclpy has no graph-change event to await, so a task polls (a few µs per name) every
`POLL_S`. How soon a dead process leaves the graph is up to DDS: at once for a clean exit, and
for a ``kill -9`` after the *dead process's* participant lease (2 s with the profile
`ros2_config.fastdds_profile`, 20 s with Fast DDS defaults; docs/ros2.md).
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import Callable, Mapping

from robovoice.middleware.base import NodeInfo, NodeJoined, NodeLeft, PresenceEvent
from robovoice.middleware.ros2_bindings import NodeBinding
from robovoice.middleware.ros2_bridge import RosBridge
from robovoice.middleware.ros2_host import host_node_name, rpc_name

log = logging.getLogger(__name__)

POLL_S = 0.1


class PresenceWatch:
    """A `watch` handle: `close()` stops the callbacks."""

    def __init__(self, owner: GraphPresence, callback: Callable[[PresenceEvent], None]) -> None:
        self._owner = owner
        self.callback = callback

    def close(self) -> None:
        self._owner.unwatch(self)


class GraphPresence:
    """Which manifest nodes are present now, and who to tell when that changes."""

    def __init__(self, bridge: RosBridge, bindings: Mapping[str, NodeBinding]) -> None:
        self._bridge = bridge
        self._bindings = bindings
        self._present: dict[str, NodeInfo] = {}
        self._announced: dict[str, NodeInfo] = {}
        """robovoice nodes hosted on ROS 2 (`ros2_host`), from their announcements."""
        self._watches: list[PresenceWatch] = []
        self._task: asyncio.Task[None] | None = None
        self._changed = asyncio.Event()

    def start(self) -> None:
        self.poll()
        self._task = asyncio.get_running_loop().create_task(self._run(), name="ros2-presence")

    async def stop(self) -> None:
        task, self._task = self._task, None
        if task is not None:
            task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await task

    async def _run(self) -> None:
        while True:
            await asyncio.sleep(POLL_S)
            try:
                self.poll()
            except Exception:  # a graph query failing must not end presence for good
                log.exception("ROS 2 graph poll failed")

    def service_up(self, name: str) -> bool:
        return self._bridge.node.count_services(name) > 0

    def action_up(self, name: str) -> bool:
        return self._bridge.node.count_services(f"{name}/_action/send_goal") > 0

    def topic_up(self, name: str) -> bool:
        return self._bridge.node.count_publishers(name) > 0

    def _up(self, binding: NodeBinding) -> bool:
        return (all(self.service_up(s) for s in binding.services)
                and all(self.action_up(a) for a in binding.actions)
                and all(self.topic_up(t) for t in binding.topics))

    def _hosted_up(self, info: NodeInfo, graph_nodes: set[str]) -> bool:
        """The hosted node's own ROS node is in the graph, with every service and action server
        (its topics may be shared with other nodes: they say nothing about this one)."""
        return (host_node_name(info.name) in graph_nodes
                and all((self.action_up if r.kind == "action" else self.service_up)(rpc_name(info.name, r.name))
                        for r in info.rpcs))

    def announce(self, info: NodeInfo) -> None:
        """A hosted robovoice node announced itself (it counts once its interfaces are in the graph)."""
        if info.name in self._bindings:
            log.warning("a hosted node %r has the name of a manifest in the folder: the folder's wins", info.name)
            return
        old = self._announced.get(info.name)
        self._announced[info.name] = info
        if old is not None and old != info and info.name in self._present:  # changed: leave and join again
            del self._present[info.name]
            self._emit(NodeLeft(info.name))
        self.poll()

    def is_hosted(self, node: str) -> bool:
        return node in self._announced and node not in self._bindings

    def poll(self) -> None:
        """Compare the graph with what was present; tell the watchers what changed."""
        candidates = [(name, b.info, self._up(b)) for name, b in self._bindings.items()]
        if self._announced:
            graph_nodes = {name for name, _ in self._bridge.node.get_node_names_and_namespaces()}
            candidates += [(name, info, self._hosted_up(info, graph_nodes)) for name, info in self._announced.items()
                           if name not in self._bindings]
        for name, info, up in candidates:
            if up and name not in self._present:
                self._present[name] = info
                log.info("ROS 2 node %s joined", name)
                self._emit(NodeJoined(info))
            elif not up and name in self._present:
                del self._present[name]
                log.info("ROS 2 node %s left", name)
                self._emit(NodeLeft(name))

    def _emit(self, event: PresenceEvent) -> None:
        self._changed.set()
        self._changed = asyncio.Event()
        for watch in list(self._watches):
            watch.callback(event)

    async def changed(self) -> None:
        """Return at the next join or leave."""
        await self._changed.wait()

    def is_present(self, node: str) -> bool:
        return node in self._present

    def nodes(self) -> Mapping[str, NodeInfo]:
        return dict(self._present)

    def watch(self, callback: Callable[[PresenceEvent], None]) -> PresenceWatch:
        handle = PresenceWatch(self, callback)
        self._watches.append(handle)
        for info in list(self._present.values()):
            callback(NodeJoined(info))
        return handle

    def unwatch(self, handle: PresenceWatch) -> None:
        if handle in self._watches:
            self._watches.remove(handle)
