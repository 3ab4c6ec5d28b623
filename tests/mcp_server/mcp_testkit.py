"""Helpers for the MCP server tests: expected tool names, bounded waits, test nodes, clients."""

from __future__ import annotations

import asyncio
import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import mcp_types as types

from robovoice.middleware.base import JSON, Message, Middleware, NodeHost, NodeInfo, RpcInfo

BOUND_S = 10.0  # the longest any test waits for an event (real seconds)
FAST = 50.0  # sim speed for tests that only need the robot alive
DRIVING = 4.0  # sim speed for tests that catch a drive under way (a 10 m drive takes 5 s)

# DESIGN.md section 5: the fixed LLM-facing tool surface of the sim robot.
SIM_TOOLS = frozenset({
    "navigate_to", "get_navigation_targets", "cancel_navigation", "return_to_dock", "stop_robot",
    "set_projector_power", "start_video_call", "end_video_call", "list_contacts",
    "get_battery_state", "get_robot_pose", "get_camera_image",
}) | {"get_map", "get_call_state", "get_projector_state"}  # + tools for people (the console), not the model
SIM_PLACES = ["kitchen", "living room", "bedroom", "bathroom", "hallway", "front door", "charging dock"]
# RPCs on the sim nodes that no manifest declares (some safety-critical).
UNDECLARED_RPCS = ("set_max_speed", "disable_collision_avoidance", "enable_collision_avoidance",
                   "set_battery_percent", "get_status")


def body(result: types.CallToolResult) -> Any:
    """The JSON of the result's first text block."""
    text = next(b for b in result.content if isinstance(b, types.TextContent)).text
    return json.loads(text)


@dataclass
class Notifications:
    """A client `message_handler` that records server notifications, with bounded waits."""

    items: list[Any] = field(default_factory=list)
    _changed: asyncio.Event = field(default_factory=asyncio.Event)

    async def __call__(self, message: Any) -> None:
        self.items.append(message)
        self._changed.set()

    def count(self, kind: type[Any]) -> int:
        return sum(isinstance(m, kind) for m in self.items)

    async def wait_count(self, kind: type[Any], n: int, bound_s: float = BOUND_S) -> None:
        async with asyncio.timeout(bound_s):
            while self.count(kind) < n:
                self._changed.clear()
                await self._changed.wait()


@dataclass
class Progress:
    """A `progress_callback` recording ``(progress, total, message)``; `first` is set at the first one."""

    items: list[tuple[float, float | None, str | None]] = field(default_factory=list)
    first: asyncio.Event = field(default_factory=asyncio.Event)

    async def __call__(self, progress: float, total: float | None, message: str | None) -> None:
        self.items.append((progress, total, message))
        self.first.set()


async def wait_for_message(middleware: Middleware, topic: str, predicate: Callable[[JSON], bool],
                           bound_s: float = BOUND_S) -> JSON:
    """The first message on `topic` (from now) whose value satisfies `predicate`."""
    found: asyncio.Future[JSON] = asyncio.get_running_loop().create_future()

    def receive(message: Message) -> None:
        if not found.done() and predicate(message.value):
            found.set_result(message.value)

    subscription = await middleware.subscribe(topic, receive)
    try:
        async with asyncio.timeout(bound_s):
            return await found
    finally:
        subscription.close()


def lamp_manifest(*, max_age_s: float = 5.0) -> dict[str, JSON]:
    """The manifest of `host_lamp`: one RPC tool with a fixed default, one snapshot."""
    return {
        "node": "lamp",
        "tools": [
            {"name": "set_lamp", "rpc": "set", "description": "Switch the lamp.",
             "parameters": {"type": "object", "properties": {"on": {"type": "boolean"}},
                            "required": ["on"], "additionalProperties": False},
             "defaults": {"room": "hall"}},
        ],
        "snapshots": [
            {"name": "get_lamp_level", "topic": "lamp/level", "description": "The lamp's level.",
             "max_age_s": max_age_s},
        ],
    }


@dataclass
class Lamp:
    """A tiny test node: records the arguments its RPCs got."""

    calls: list[tuple[str, dict[str, JSON]]] = field(default_factory=list)

    async def set(self, args: dict[str, JSON]) -> JSON:
        self.calls.append(("set", args))
        return {"on": args.get("on"), "room": args.get("room")}

    async def self_destruct(self, args: dict[str, JSON]) -> JSON:
        self.calls.append(("self_destruct", args))
        return {"boom": True}


async def host_lamp(middleware: Middleware, lamp: Lamp, manifest: Mapping[str, JSON] | None = None) -> NodeHost:
    info = NodeInfo(
        "lamp",
        rpcs=(RpcInfo("set", params=("on", "room")), RpcInfo("self_destruct")),
        topics=("lamp/level",),
        manifest=dict(manifest if manifest is not None else lamp_manifest()),
        manifest_source="<lamp test node>",
    )
    return await middleware.host(info, {"set": lamp.set, "self_destruct": lamp.self_destruct}, {})
