"""The robot's state for the console, read through its own MCP tools and snapshots.

Nothing here knows the simulated robot: the watcher calls the read-only tools the robot
offers (a snapshot's value sits in ``{"value", "stamp", "age_s", "stale"}``; an RPC's result
is the value itself) at each one's own period, and keeps the latest of each. Which tools
are watched is a table (`WATCHED`): a tool the robot does not offer is simply not shown.
While the robot moves, its positions are kept as the path it drives.

The state (``RobotWatcher.state()``)::

    {"pose": {...}, "battery": {...}, "call": {...}, "projector": {...}, "map": {...},
     "camera": {"mime": "image/jpeg", "data": "<base64>"}, "path": [[x, y], ...],
     "stamps": {"pose": <unix time>, ...}, "errors": {"battery": "<why it could not be read>"}}
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections import deque
from collections.abc import Awaitable, Callable, Mapping
from dataclasses import dataclass
from typing import Any

import mcp_types as types
from mcp import Client

log = logging.getLogger(__name__)


@dataclass(frozen=True, slots=True)
class Watched:
    """Read `tool` every `period_s` seconds into the state's `key`; `when_watched`: only
    while someone looks (the camera picture is the only heavy one)."""

    key: str
    tool: str
    period_s: float
    when_watched: bool = False


WATCHED: tuple[Watched, ...] = (
    Watched("pose", "get_robot_pose", 0.2),
    Watched("battery", "get_battery_state", 1.0),
    Watched("call", "get_call_state", 0.5),
    Watched("projector", "get_projector_state", 0.5),
    Watched("map", "get_map", 5.0),
    Watched("camera", "get_camera_image", 0.34, when_watched=True),
)
MAX_PATH_POINTS = 2000
CALL_TIMEOUT_S = 5.0
TOOLS_REFRESH_S = 10.0


def snapshot_value(result: types.CallToolResult) -> Any:
    """The value of a tool result: a snapshot's ``value``, a result's structured body, an
    image as ``{"mime", "data"}``; a failed call raises `RuntimeError` with its message."""
    if result.is_error:
        text = " ".join(c.text for c in result.content if isinstance(c, types.TextContent))
        raise RuntimeError(text[:300] or "the tool reported an error")
    for block in result.content:
        if isinstance(block, types.ImageContent):
            return {"mime": block.mime_type, "data": block.data}
    body = result.structured_content
    if isinstance(body, Mapping) and "value" in body and "stale" in body:
        return body["value"]
    return body


class RobotWatcher:
    """Keeps the latest robot state; `run` polls until cancelled, calling `on_state` after
    each round that changed something (the console broadcasts it)."""

    def __init__(self, client: Client, *, watched: tuple[Watched, ...] = WATCHED,
                 on_state: Callable[[dict[str, Any]], Awaitable[None] | None] | None = None,
                 watching: Callable[[], bool] = lambda: True, tick_s: float = 0.1) -> None:
        self._client = client
        self._watched = watched
        self._on_state = on_state
        self._watching = watching
        self._tick_s = tick_s
        self._values: dict[str, Any] = {}
        self._stamps: dict[str, float] = {}
        self._errors: dict[str, str] = {}
        self._path: deque[tuple[float, float]] = deque(maxlen=MAX_PATH_POINTS)
        self._moving = False
        self._last_point: tuple[float, float] | None = None
        self.available: set[str] = set()
        self.rounds = 0

    def state(self) -> dict[str, Any]:
        return {**self._values, "path": [list(p) for p in self._path], "stamps": dict(self._stamps),
                "errors": dict(self._errors), "tools": sorted(self.available)}

    async def refresh_tools(self) -> None:
        listing = await self._client.list_tools()
        names = {tool.name for tool in listing.tools}
        self.available = {w.tool for w in self._watched if w.tool in names}

    async def read(self, item: Watched) -> None:
        """Read one watched tool now."""
        try:
            result = await self._client.call_tool(item.tool, {}, read_timeout_seconds=CALL_TIMEOUT_S)
            value = snapshot_value(result)
        except Exception as exc:  # a node offline, a stale topic, a timeout: shown, never fatal
            self._errors[item.key] = str(exc) or type(exc).__name__
            return
        self._errors.pop(item.key, None)
        self._values[item.key] = value
        self._stamps[item.key] = round(time.time(), 3)
        if item.key == "pose" and isinstance(value, Mapping):
            self._track(value)

    def _track(self, pose: Mapping[str, Any]) -> None:
        x, y, moving = pose.get("x"), pose.get("y"), bool(pose.get("moving"))
        if not isinstance(x, int | float) or not isinstance(y, int | float):
            return
        point = (round(float(x), 2), round(float(y), 2))
        before, self._last_point = self._last_point, point
        # A drive that began, or even ended, between two reads (a short one, a loaded machine)
        # still starts its path where the robot was last seen standing.
        jumped = not moving and not self._moving and before is not None and point != before
        if (moving and not self._moving) or jumped:
            self._path.clear()  # a new drive: a new path
            if before is not None:
                self._path.append(before)
        if (moving or self._moving or jumped) and (not self._path or self._path[-1] != point):
            self._path.append(point)
        self._moving = moving

    async def run(self) -> None:
        due = dict.fromkeys((w.key for w in self._watched), 0.0)
        tools_due = 0.0
        while True:
            now = time.monotonic()
            if now >= tools_due:  # nodes come and go: which tools there are is looked at again now and then
                tools_due = now + TOOLS_REFRESH_S
                try:
                    await self.refresh_tools()
                    self._errors.pop("tools", None)
                except Exception as exc:  # the robot unreachable for now: said on the page, tried again
                    self._errors["tools"] = str(exc) or type(exc).__name__
            batch = [w for w in self._watched
                     if w.tool in self.available and now >= due[w.key] and (not w.when_watched or self._watching())]
            for w in batch:
                due[w.key] = now + w.period_s
            if batch:
                await asyncio.gather(*(self.read(w) for w in batch))
                self.rounds += 1
                if self._on_state is not None:
                    result = self._on_state(self.state())
                    if isinstance(result, Awaitable):
                        await result
            await asyncio.sleep(self._tick_s)
