"""The simulated co-presence robot: middleware nodes that run on any `Middleware`.

See `robovoice.sim.robot` for the entry points and DESIGN.md section 5 for the tool surface
its manifests (`robovoice/sim/manifests/<node>/mcp.json`) give the LLM.
"""

from __future__ import annotations

from robovoice.sim.clock import SimClock
from robovoice.sim.robot import NODE_NAMES, SETUP_NAMES, SimRobot, SimState, run_sim_forever, start_sim_robot

__all__ = ["NODE_NAMES", "SETUP_NAMES", "SimClock", "SimRobot", "SimState", "run_sim_forever",
           "start_sim_robot"]
