"""Node `base`: the motor base and its battery, with the safety settings.

- RPC `stop()`: stops all motion now (halts the drive under way); always succeeds.
- topic `battery` at 1 Hz sim: `{"percent": float, "charging": bool, "voltage": float}`.
  The battery drains while driving (0.1 %/m) and slowly at rest, and charges on the dock.
- RPC `get_status()`: battery, motion and the safety settings.

Safety-critical RPCs that **no manifest declares** (reachable on the middleware, never
through MCP):

- `set_max_speed(mps)`: the cruise speed, 0.05..1.5 m/s (default 0.5);
- `disable_collision_avoidance()` / `enable_collision_avoidance()`;
- `set_battery_percent(percent)`: sim only, to test low-battery behaviour.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping

from robovoice.errors import InvalidArgumentsError
from robovoice.middleware.base import JSON, ActionHandler, NodeHost, NodeInfo, RpcHandler, RpcInfo
from robovoice.sim.body import CHARGE_PER_S, HARDWARE_MAX_SPEED_MPS, IDLE_DRAIN_PER_S, SimBody
from robovoice.sim.node import check_args, make_node_info, number_arg

log = logging.getLogger(__name__)

NAME = "base"
BATTERY_TOPIC = "battery"
BATTERY_PERIOD_S = 1.0
MIN_SPEED_MPS = 0.05
HALT_WAIT_S = 2.0

RPCS = (
    RpcInfo("stop", "rpc", (), "stop all motion now"),
    RpcInfo("get_status", "rpc", (), "battery, motion and safety settings"),
    RpcInfo("set_max_speed", "rpc", ("mps",), "SAFETY: set the cruise speed in m/s"),
    RpcInfo("disable_collision_avoidance", "rpc", (), "SAFETY: drive without collision avoidance"),
    RpcInfo("enable_collision_avoidance", "rpc", (), "SAFETY: restore collision avoidance"),
    RpcInfo("set_battery_percent", "rpc", ("percent",), "SIM ONLY: force the battery level"),
)
SAFETY_RPCS = ("set_max_speed", "disable_collision_avoidance", "enable_collision_avoidance",
               "set_battery_percent")
_RPC = {r.name: r for r in RPCS}


class BaseNode:
    name = NAME

    def __init__(self, body: SimBody) -> None:
        self._body = body

    def node_info(self) -> NodeInfo:
        return make_node_info(NAME, RPCS, (BATTERY_TOPIC,))

    def rpc_handlers(self) -> Mapping[str, RpcHandler]:
        return {
            "stop": self._stop,
            "get_status": self._get_status,
            "set_max_speed": self._set_max_speed,
            "disable_collision_avoidance": self._disable_collision_avoidance,
            "enable_collision_avoidance": self._enable_collision_avoidance,
            "set_battery_percent": self._set_battery_percent,
        }

    def action_handlers(self) -> Mapping[str, ActionHandler]:
        return {}

    def battery_state(self) -> dict[str, JSON]:
        return {"percent": round(self._body.battery_percent, 1), "charging": self._body.charging,
                "voltage": round(self._body.voltage, 2)}

    async def run(self, host: NodeHost) -> None:
        """Integrate charging and idle drain, publish `battery` once per sim second."""
        clock = self._body.clock
        last = clock.now()
        async for now in clock.ticks(BATTERY_PERIOD_S):
            elapsed, last = now - last, now
            if self._body.charging:
                self._body.drain(-CHARGE_PER_S * elapsed)
            elif not self._body.moving:
                self._body.drain(IDLE_DRAIN_PER_S * elapsed)
            host.publish(BATTERY_TOPIC, self.battery_state())

    # --- handlers --------------------------------------------------------------------
    async def _stop(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["stop"])
        motion = self._body.halt("stopped by the base (stop)")
        if motion is not None:
            await motion.wait_ended(HALT_WAIT_S)
        return {"stopped": True, "was_moving": motion is not None,
                "interrupted": motion.label if motion is not None else None}

    async def _get_status(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["get_status"])
        return {**self.battery_state(), "moving": self._body.moving,
                "max_speed_mps": self._body.max_speed_mps,
                "collision_avoidance": self._body.collision_avoidance}

    async def _set_max_speed(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["set_max_speed"])
        mps = number_arg(args, "set_max_speed", "mps")
        if not MIN_SPEED_MPS <= mps <= HARDWARE_MAX_SPEED_MPS:
            raise InvalidArgumentsError(
                f"max speed must be {MIN_SPEED_MPS}..{HARDWARE_MAX_SPEED_MPS} m/s, got {mps}",
                details={"mps": mps, "min": MIN_SPEED_MPS, "max": HARDWARE_MAX_SPEED_MPS},
            )
        previous, self._body.max_speed_mps = self._body.max_speed_mps, mps
        log.warning("maximum speed changed from %.2f to %.2f m/s", previous, mps)
        return {"max_speed_mps": mps, "previous_mps": previous}

    async def _disable_collision_avoidance(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["disable_collision_avoidance"])
        self._body.collision_avoidance = False
        log.warning("collision avoidance DISABLED")
        return {"collision_avoidance": False}

    async def _enable_collision_avoidance(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["enable_collision_avoidance"])
        self._body.collision_avoidance = True
        log.info("collision avoidance enabled")
        return {"collision_avoidance": True}

    async def _set_battery_percent(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["set_battery_percent"])
        percent = number_arg(args, "set_battery_percent", "percent")
        if not 0 <= percent <= 100:
            raise InvalidArgumentsError(f"battery percent must be 0..100, got {percent}",
                                        details={"percent": percent})
        self._body.battery_percent = percent
        return self.battery_state()
