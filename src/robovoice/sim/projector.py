"""Node `projector`: the robot's projector (shows pictures and video calls on a wall).

- RPC `set_power(on: bool)`: switch it; the state is kept. Result `{"on": bool, "changed": bool}`.
- RPC `get_state()`: `{"on": bool}`.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping

from robovoice.middleware.base import JSON, ActionHandler, NodeHost, NodeInfo, RpcHandler, RpcInfo
from robovoice.sim.node import bool_arg, check_args, make_node_info

log = logging.getLogger(__name__)

NAME = "projector"
RPCS = (
    RpcInfo("set_power", "rpc", ("on",), "switch the projector on or off"),
    RpcInfo("get_state", "rpc", (), "whether the projector is on"),
)
_RPC = {r.name: r for r in RPCS}


class ProjectorNode:
    name = NAME

    def __init__(self) -> None:
        self.on = False

    def node_info(self) -> NodeInfo:
        return make_node_info(NAME, RPCS)

    def rpc_handlers(self) -> Mapping[str, RpcHandler]:
        return {"set_power": self._set_power, "get_state": self._get_state}

    def action_handlers(self) -> Mapping[str, ActionHandler]:
        return {}

    async def run(self, host: NodeHost) -> None:
        return None

    async def _set_power(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["set_power"])
        on = bool_arg(args, "set_power", "on")
        changed = on != self.on
        self.on = on
        if changed:
            log.info("projector switched %s", "on" if on else "off")
        return {"on": on, "changed": changed}

    async def _get_state(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["get_state"])
        return {"on": self.on}
