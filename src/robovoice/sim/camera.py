"""Node `camera`: a small front camera.

- topic `camera` at 3 Hz sim: `{"mime_type": "image/jpeg", "data": <base64>, "width": 160,
  "height": 120}`, a real baseline JPEG (see `robovoice.sim.jpeg`) showing the nearest
  place's name and a doorway that moves with the heading (see `robovoice.sim.frames`).

Frames are encoded once per view (place x heading in 45 degree steps) and cached; the
encoding runs in a worker thread so that the event loop never waits on it.
"""

from __future__ import annotations

import asyncio
import base64
from collections.abc import Mapping

from robovoice.middleware.base import JSON, ActionHandler, NodeHost, NodeInfo, RpcHandler
from robovoice.sim.body import SimBody
from robovoice.sim.frames import HEIGHT, WIDTH, View, render_jpeg
from robovoice.sim.node import make_node_info
from robovoice.sim.world import nearest_place

NAME = "camera"
CAMERA_TOPIC = "camera"
CAMERA_PERIOD_S = 1 / 3


class CameraNode:
    name = NAME

    def __init__(self, body: SimBody) -> None:
        self._body = body
        self._frames: dict[View, str] = {}

    def node_info(self) -> NodeInfo:
        return make_node_info(NAME, (), (CAMERA_TOPIC,))

    def rpc_handlers(self) -> Mapping[str, RpcHandler]:
        return {}

    def action_handlers(self) -> Mapping[str, ActionHandler]:
        return {}

    def current_view(self) -> View:
        pose = self._body.pose
        return View.of(nearest_place(pose.point).name, pose.heading_deg)

    async def frame(self, view: View) -> dict[str, JSON]:
        """The message for `view` (encoded on first use)."""
        data = self._frames.get(view)
        if data is None:
            jpeg = await asyncio.to_thread(render_jpeg, view)
            data = self._frames[view] = base64.b64encode(jpeg).decode("ascii")
        return {"mime_type": "image/jpeg", "data": data, "width": WIDTH, "height": HEIGHT}

    async def run(self, host: NodeHost) -> None:
        async for _ in self._body.clock.ticks(CAMERA_PERIOD_S):
            host.publish(CAMERA_TOPIC, await self.frame(self.current_view()))
