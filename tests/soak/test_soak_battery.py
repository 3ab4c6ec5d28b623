"""A drive the robot cannot make for its battery, through the embedded model (integration): the
robot stays where it is and the assistant says why (the structured ``battery_low`` error worded
from its message and hint), not a silent success. In the first 2-hour soak four drives in a row
"answered" without moving the robot; the soak now docks a robot whose battery is low and judges
a refused drive done only when its answer names the battery (tests/soak/test_soak_judge.py)."""

from __future__ import annotations

import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.loop import Assistant
from robovoice.assistant.prompt import SYSTEM_PROMPT
from robovoice.config import RobotConfig
from robovoice.llm.local import LocalLlamaBackend
from robovoice.middleware.base import Feedback

from ..llm.local_kit import PATIENT

pytestmark = [pytest.mark.integration, pytest.mark.timeout(900),
              pytest.mark.usefixtures("local_model_installed")]  # tests/conftest.py: fails, never skips


async def _ignore(_feedback: Feedback) -> None:
    pass


async def test_a_drive_refused_for_a_low_battery_is_explained() -> None:
    backend = LocalLlamaBackend(n_threads=2, deadlines=PATIENT)
    try:
        # real time: the idle drain (0.005 %/s) over a slow turn keeps the battery above empty
        async with connect_robot(RobotConfig(address="sim://")) as link:
            sim = link.sim
            assert sim is not None
            # off the dock (where it would charge), then a battery below the robot's 5 % drive limit
            await sim.middleware.run_action("navigation", "drive_to", {"target": "bedroom"},
                                             on_feedback=_ignore, timeout=60.0)
            await sim.middleware.call("base", "set_battery_percent", {"percent": 4.5}, timeout=5.0)
            await backend.warm_up(SYSTEM_PROMPT, await link.tools.specs())  # as `robovoice chat` starts
            result = await Assistant(backend, link.tools).turn("Go to the kitchen.")
            state = sim.state
    finally:
        await backend.aclose()
    assert [(o.name, o.error) for o in result.outcomes] == [("navigate_to", "battery_low")], result
    assert state.nearest_place == "bedroom" and not state.moving
    assert "battery" in result.reply.lower(), result.reply
