"""Node `localization`: where the robot is.

- topic `pose` at 10 Hz sim:
  `{"x": float, "y": float, "heading_deg": float, "nearest_place": str, "moving": bool}`
  (metres on the map of `robovoice.sim.world`; heading 0 = +x, counter-clockwise);
- RPC `get_pose()`: the same value, on demand.
"""

from __future__ import annotations

from collections.abc import Mapping

from robovoice.middleware.base import JSON, ActionHandler, NodeHost, NodeInfo, RpcHandler, RpcInfo
from robovoice.sim.body import SimBody
from robovoice.sim.node import check_args, make_node_info
from robovoice.sim.world import nearest_place

NAME = "localization"
POSE_TOPIC = "pose"
POSE_PERIOD_S = 0.1

RPCS = (RpcInfo("get_pose", "rpc", (), "the robot's pose and nearest place"),)


class LocalizationNode:
    name = NAME

    def __init__(self, body: SimBody) -> None:
        self._body = body

    def node_info(self) -> NodeInfo:
        return make_node_info(NAME, RPCS, (POSE_TOPIC,))

    def rpc_handlers(self) -> Mapping[str, RpcHandler]:
        return {"get_pose": self._get_pose}

    def action_handlers(self) -> Mapping[str, ActionHandler]:
        return {}

    def pose(self) -> dict[str, JSON]:
        pose = self._body.pose
        return {"x": round(pose.x, 2), "y": round(pose.y, 2), "heading_deg": round(pose.heading_deg, 1),
                "nearest_place": nearest_place(pose.point).name, "moving": self._body.moving}

    async def run(self, host: NodeHost) -> None:
        async for _ in self._body.clock.ticks(POSE_PERIOD_S):
            host.publish(POSE_TOPIC, self.pose())

    async def _get_pose(self, args: dict[str, JSON]) -> JSON:
        check_args(args, RPCS[0])
        return self.pose()
