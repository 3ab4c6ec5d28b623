"""Sim nodes in child processes over Zenoh on loopback, seen through the Zenoh adapter."""

from __future__ import annotations

import asyncio
import signal
import sys
import time
from collections.abc import AsyncIterator, Callable

import pytest

from robovoice.errors import MiddlewareError, NodeUnavailableError, RobotFailure
from robovoice.middleware.base import Feedback, Message, NodeJoined, NodeLeft, PresenceEvent
from robovoice.middleware.zenoh import ZenohMiddleware

from ..waiting import until
from .helpers import ROOT, Child, free_port, robovoice

pytestmark = pytest.mark.integration

SIM_NODES = {"navigation", "base", "localization", "camera", "projector", "communication"}


@pytest.fixture
def port() -> int:
    return free_port()


@pytest.fixture
async def client(port: int) -> AsyncIterator[ZenohMiddleware]:
    middleware = ZenohMiddleware.from_uri(f"zenoh://127.0.0.1:{port}?robot=dist")
    await middleware.start()
    try:
        yield middleware
    finally:
        await middleware.close()


def sim(spawn: Callable[..., Child], port: int, *nodes: str, speed: float = 1.0) -> Child:
    args = ["sim", "--middleware", f"zenoh://127.0.0.1:{port}?robot=dist", "--speed", str(speed)]
    for node in nodes:
        args += ["--node", node]
    child = spawn(f"sim[{','.join(nodes) or 'all'}]", robovoice(*args))
    child.wait_for_line("robovoice sim: ready")
    return child


async def test_sim_nodes_join_with_manifests_and_serve(spawn: Callable[..., Child], port: int,
                                                       client: ZenohMiddleware) -> None:
    sim(spawn, port, speed=5)
    await until(lambda: set(client.nodes()) == SIM_NODES, what="all sim nodes present")
    navigation = client.nodes()["navigation"]
    assert navigation.manifest is not None and navigation.manifest["node"] == "navigation"
    drive_to = navigation.rpc("drive_to")
    assert drive_to is not None and drive_to.kind == "action"
    targets = await client.call("navigation", "list_targets", {}, timeout=5)
    assert "kitchen" in targets["places"]
    with pytest.raises(RobotFailure) as err:
        await client.call("communication", "start_call", {"contact": "Zoe"}, timeout=5)
    assert err.value.code not in ("internal_error", "node_unavailable")

    batteries: list[Message] = []
    await client.subscribe("battery", batteries.append)
    await until(lambda: bool(batteries), what="a battery message")
    assert batteries[0].stamp > time.time() - 60


async def test_sigkill_mid_action_fails_fast_then_restart(spawn: Callable[..., Child], port: int,
                                                          client: ZenohMiddleware) -> None:
    sim(spawn, port, "base", "localization")
    navigation = sim(spawn, port, "navigation")
    await until(lambda: "navigation" in client.nodes(), what="navigation present")
    events: list[PresenceEvent] = []
    await client.watch(events.append)
    progress: list[Feedback] = []

    async def on_feedback(feedback: Feedback) -> None:
        progress.append(feedback)

    drive = asyncio.create_task(client.run_action("navigation", "drive_to", {"target": "front door"},
                                                  on_feedback=on_feedback, timeout=60))
    await until(lambda: bool(progress) or drive.done(), what="drive feedback")
    assert not drive.done()
    killed = asyncio.get_running_loop().time()
    navigation.kill()
    with pytest.raises(NodeUnavailableError):
        await asyncio.wait_for(drive, 5)
    assert asyncio.get_running_loop().time() - killed < 3.0  # promptly, not after the 60 s timeout
    await until(lambda: NodeLeft("navigation") in events, what="NodeLeft(navigation)")
    assert "navigation" not in client.nodes() and "base" in client.nodes()

    left = events.index(NodeLeft("navigation"))
    sim(spawn, port, "navigation")
    await until(lambda: any(isinstance(e, NodeJoined) and e.node.name == "navigation" for e in events[left:]),
                what="navigation back")
    status = await client.call("navigation", "get_status", {}, timeout=5)
    assert status["driving"] is False


CLIENT_SCRIPT = """
import asyncio, sys
from robovoice.middleware.zenoh import ZenohMiddleware

async def main():
    mw = ZenohMiddleware.from_uri(sys.argv[1])
    await mw.start()
    async with asyncio.timeout(5):  # a client acts on presence: wait until the node is seen
        while "navigation" not in mw.nodes():
            await asyncio.sleep(0.01)
    async def on_feedback(feedback):
        print("feedback", feedback.progress, flush=True)
    await mw.run_action("navigation", "drive_to", {"target": "front door"}, on_feedback=on_feedback, timeout=120)

asyncio.run(main())
"""


async def test_a_dead_client_s_goal_is_cancelled_on_the_node(spawn: Callable[..., Child], port: int,
                                                              client: ZenohMiddleware) -> None:
    sim(spawn, port, "navigation")
    await until(lambda: "navigation" in client.nodes(), what="navigation present")
    driver = spawn("driver", [sys.executable, "-c", CLIENT_SCRIPT, f"zenoh://127.0.0.1:{port}?robot=dist"])
    await driver.async_wait_for_line("feedback")
    assert (await client.call("navigation", "get_status", {}, timeout=5))["driving"] is True
    driver.kill()

    async def driving() -> bool:
        return bool((await client.call("navigation", "get_status", {}, timeout=5))["driving"])

    async with asyncio.timeout(5):
        while await driving():
            await asyncio.sleep(0.05)


async def test_unreachable_endpoint_is_a_clear_error(spawn: Callable[..., Child]) -> None:
    port = free_port()
    middleware = ZenohMiddleware.from_uri(f"zenoh://127.0.0.1:{port}?mode=client&timeout=0.5")
    started = time.monotonic()
    with pytest.raises(MiddlewareError, match=f"tcp/127.0.0.1:{port}"):
        await middleware.start()
    assert time.monotonic() - started < 3

    child = spawn("sim-unreachable", robovoice(
        "sim", "--middleware", f"zenoh://?connect=tcp/127.0.0.1:{port}&must_connect=true&timeout=0.5"))
    code = await asyncio.to_thread(child.proc.wait, 15)
    child.stop()
    assert code == 1
    assert f"tcp/127.0.0.1:{port}" in child.output() and "robovoice: error:" in child.output()


async def test_external_node_written_with_zenoh_only(spawn: Callable[..., Child], port: int,
                                                     client: ZenohMiddleware) -> None:
    node = spawn("lights", [sys.executable, str(ROOT / "examples" / "zenoh_external_node.py"),
                            "--connect", f"tcp/127.0.0.1:{port}", "--robot", "dist", "--period", "0.1"])
    node.wait_for_line("lights: ready")
    await until(lambda: "lights" in client.nodes(), what="lights present")
    info = client.nodes()["lights"]
    assert info.manifest is not None and [t["name"] for t in info.manifest["tools"]] == ["set_light", "list_lights"]
    assert await client.call("lights", "set_light", {"room": "kitchen", "on": True}, timeout=5) == {
        "room": "kitchen", "on": True}
    assert await client.call("lights", "list_lights", {}, timeout=5) == {"on": ["kitchen"]}
    with pytest.raises(RobotFailure) as err:
        await client.call("lights", "set_light", {"room": "garage", "on": True}, timeout=5)
    assert err.value.code == "unknown_room" and "kitchen" in (err.value.hint or "")
    temperatures: list[Message] = []
    await client.subscribe("temperature", temperatures.append)
    await until(lambda: bool(temperatures), what="a temperature message")
    assert 20 < temperatures[0].value["celsius"] < 23
    assert node.stop() == 0
    await until(lambda: "lights" not in client.nodes(), what="lights gone")


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
async def test_sim_leaves_cleanly_on_signal(spawn: Callable[..., Child], port: int, client: ZenohMiddleware,
                                            signum: signal.Signals) -> None:
    child = sim(spawn, port, "projector")
    await until(lambda: "projector" in client.nodes(), what="projector present")
    events: list[PresenceEvent] = []
    await client.watch(events.append)
    child.proc.send_signal(signum)
    assert await asyncio.to_thread(child.proc.wait, 10) == 0, child.output()
    await until(lambda: NodeLeft("projector") in events, what="NodeLeft(projector)")
    assert "Traceback" not in child.output()
