"""`SimRobot`: the simulated co-presence robot, its nodes hosted on any `Middleware`.

    robot = await start_sim_robot(middleware, speed=20.0)   # middleware already started
    await robot.apply_setup("driving+in_call")               # DESIGN.md section 6 `setup`
    robot.state.driving_target                               # a read-only view for tests
    await robot.stop()

Nodes (`NODE_NAMES`): navigation, base, localization, camera, projector, communication.
They share one simulated body (see `robovoice.sim.body`) and one `SimClock`; to the
outside they speak only through the middleware. Setups are made through the nodes' own
RPCs over the middleware, never through MCP.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable, Collection
from dataclasses import dataclass
from typing import TypeVar

from robovoice.errors import ConfigError, RobotFailure
from robovoice.middleware.base import JSON, Feedback, Middleware, NodeHost
from robovoice.sim.base import BaseNode
from robovoice.sim.body import Pose, SimBody
from robovoice.sim.camera import CameraNode
from robovoice.sim.clock import SimClock
from robovoice.sim.communication import CommunicationNode
from robovoice.sim.localization import LocalizationNode
from robovoice.sim.navigation import NavigationNode
from robovoice.sim.node import SimNode
from robovoice.sim.projector import ProjectorNode
from robovoice.sim.world import PLACES, nearest_place, route, route_length

log = logging.getLogger(__name__)

NODE_NAMES: tuple[str, ...] = ("navigation", "base", "localization", "camera", "projector", "communication")
SETUP_NAMES: tuple[str, ...] = ("driving", "in_call", "projector_on")
SETUP_CALL_CONTACT = "Anna"
RPC_TIMEOUT_S = 5.0
SETUP_WAIT_S = 5.0  # real seconds a setup waits for the drive to get under way
# The "driving" setup's drive crawls, so that it is still under way when a slow model decides
# (at 10x a drive at 0.5 m/s arrived in ~2 s, before a model on a 2-core machine had answered a
# "stop"). Any drive the person asks for runs at the body's own speed again.
SETUP_CRAWL_MPS = 0.05

_N = TypeVar("_N")


@dataclass(frozen=True, slots=True)
class SimState:
    """What the sim robot is doing, at one moment (for tests and demos)."""

    pose: Pose
    nearest_place: str
    moving: bool
    driving_target: str | None
    projector_on: bool
    call_contact: str | None
    remote_speaking: bool
    battery_percent: float
    charging: bool
    max_speed_mps: float
    collision_avoidance: bool

    @property
    def in_call(self) -> bool:
        return self.call_contact is not None


def _make_node(name: str, body: SimBody) -> SimNode:
    factories: dict[str, Callable[[], SimNode]] = {
        "navigation": lambda: NavigationNode(body),
        "base": lambda: BaseNode(body),
        "localization": lambda: LocalizationNode(body),
        "camera": lambda: CameraNode(body),
        "projector": ProjectorNode,
        "communication": lambda: CommunicationNode(body.clock),
    }
    return factories[name]()


class SimRobot:
    """The running sim robot. Create it with `start_sim_robot`."""

    def __init__(self, middleware: Middleware, body: SimBody, nodes: dict[str, SimNode]) -> None:
        self._middleware = middleware
        self._body = body
        self._nodes = nodes
        self._hosts: list[NodeHost] = []
        self._supervisor: asyncio.Task[None] | None = None
        self._setup_drive: asyncio.Task[JSON] | None = None
        self._stopped = asyncio.Event()
        self._done = asyncio.Event()
        self._failure: BaseException | None = None

    @property
    def middleware(self) -> Middleware:
        return self._middleware

    @property
    def clock(self) -> SimClock:
        return self._body.clock

    @property
    def node_names(self) -> tuple[str, ...]:
        return tuple(self._nodes)

    @property
    def failure(self) -> BaseException | None:
        """The error that ended the nodes' background work, if one did."""
        return self._failure

    def _find(self, kind: type[_N]) -> _N | None:
        return next((n for n in self._nodes.values() if isinstance(n, kind)), None)

    @property
    def state(self) -> SimState:
        body = self._body
        navigation = self._find(NavigationNode)
        projector = self._find(ProjectorNode)
        communication = self._find(CommunicationNode)
        return SimState(
            pose=body.pose,
            nearest_place=nearest_place(body.pose.point).name,
            moving=body.moving,
            driving_target=navigation.driving_target if navigation else None,
            projector_on=projector.on if projector else False,
            call_contact=communication.call_contact if communication else None,
            remote_speaking=communication.remote_speaking if communication else False,
            battery_percent=round(body.battery_percent, 1),
            charging=body.charging,
            max_speed_mps=body.max_speed_mps,
            collision_avoidance=body.collision_avoidance,
        )

    # --- life cycle ------------------------------------------------------------------
    async def _start(self) -> None:
        try:
            for node in self._nodes.values():
                self._hosts.append(
                    await self._middleware.host(node.node_info(), node.rpc_handlers(), node.action_handlers())
                )
        except BaseException:
            await self._leave()
            raise
        self._supervisor = asyncio.create_task(self._supervise(), name="sim-robot")
        self._supervisor.add_done_callback(self._supervisor_done)
        log.info("sim robot up at %gx: %s", self.clock.speed, ", ".join(self._nodes))

    async def _supervise(self) -> None:
        async with asyncio.TaskGroup() as group:
            for node, host in zip(self._nodes.values(), self._hosts, strict=True):
                group.create_task(node.run(host), name=f"sim-{node.name}")
        await self._stopped.wait()

    def _supervisor_done(self, task: asyncio.Task[None]) -> None:
        if not task.cancelled() and task.exception() is not None:
            self._failure = task.exception()
            log.error("sim robot node failed", exc_info=self._failure)
        self._done.set()

    async def wait(self) -> None:
        """Return when the robot is stopped; raise if a node's background work failed."""
        await self._done.wait()
        if self._failure is not None:
            raise self._failure

    async def stop(self) -> None:
        """Stop the background work and withdraw every node. Idempotent."""
        if self._stopped.is_set():
            return
        self._stopped.set()
        for task in (self._setup_drive, self._supervisor):
            if task is not None and not task.done():
                task.cancel()
                await asyncio.wait([task])  # its outcome is logged by its done callback
        await self._leave()
        log.info("sim robot stopped")

    async def _leave(self) -> None:
        while self._hosts:
            await self._hosts.pop().leave()

    # --- setups (DESIGN.md section 6) -------------------------------------------------
    async def apply_setup(self, setup: str) -> None:
        """Establish `setup` ("driving", "in_call", "projector_on", combined with "+").

        An empty string or "none" establishes nothing. Raises `ConfigError` for an unknown
        setup name and `RobotFailure` when the robot refuses (e.g. battery empty).
        """
        parts = [part.strip() for part in setup.split("+") if part.strip()]
        if parts == ["none"]:
            return
        unknown = [part for part in parts if part not in SETUP_NAMES]
        if unknown:
            raise ConfigError(f"unknown setup {'+'.join(unknown)!r}: known setups are "
                              f"{', '.join(SETUP_NAMES)} (combine with '+')")
        for part in parts:
            if part == "projector_on":
                await self._call("projector", "set_power", {"on": True})
            elif part == "in_call":
                await self._setup_call()
            else:
                await self._setup_driving()

    async def _call(self, node: str, rpc: str, args: dict[str, JSON]) -> JSON:
        return await self._middleware.call(node, rpc, args, timeout=RPC_TIMEOUT_S)

    async def _setup_call(self) -> None:
        try:
            await self._call("communication", "start_call", {"contact": SETUP_CALL_CONTACT})
        except RobotFailure as failure:
            if failure.code != "busy":
                raise
            await self._call("communication", "end_call", {})
            await self._call("communication", "start_call", {"contact": SETUP_CALL_CONTACT})

    def _far_place(self) -> str:
        here = self._body.pose.point
        reachable = [p for p in PLACES if p.reachable]
        return max(reachable, key=lambda p: route_length(route(here, p.position))).name

    async def _setup_driving(self) -> None:
        if self._setup_drive is not None and not self._setup_drive.done():
            self._setup_drive.cancel()
            await asyncio.wait([self._setup_drive])  # its outcome is logged by its done callback
        target = self._far_place()
        under_way = asyncio.Event()
        cruise, self._body.max_speed_mps = self._body.max_speed_mps, SETUP_CRAWL_MPS

        async def on_feedback(feedback: Feedback) -> None:
            under_way.set()

        drive = asyncio.create_task(
            self._middleware.run_action("navigation", "drive_to", {"target": target},
                                        on_feedback=on_feedback, timeout=self.clock.to_real(900) + 10),
            name="sim-setup-drive",
        )
        drive.add_done_callback(_log_setup_drive)
        drive.add_done_callback(lambda _: self._end_crawl(cruise))
        self._setup_drive = drive
        waiter = asyncio.create_task(under_way.wait())
        try:
            await asyncio.wait({drive, waiter}, timeout=SETUP_WAIT_S, return_when=asyncio.FIRST_COMPLETED)
        finally:
            waiter.cancel()
        if drive.done():
            drive.result()  # raises the refusal
            raise RobotFailure(f"the setup drive to the {target} ended at once", code="setup_failed")
        if not under_way.is_set():
            raise RobotFailure(f"the setup drive to the {target} did not start within {SETUP_WAIT_S} s",
                               code="setup_failed")
        log.info("setup: driving to the %s", target)

    def _end_crawl(self, cruise: float) -> None:
        if self._body.max_speed_mps == SETUP_CRAWL_MPS:  # unless set_max_speed changed it since
            self._body.max_speed_mps = cruise

    async def reset(self) -> None:
        """Undo the setups through the RPCs: no drive, no call, projector off."""
        for node, rpc, args, harmless in (
            ("navigation", "cancel", {}, "not_driving"),
            ("communication", "end_call", {}, "not_in_call"),
            ("projector", "set_power", {"on": False}, None),
        ):
            if node not in self._nodes:
                continue
            try:
                await self._call(node, rpc, args)
            except RobotFailure as failure:
                if failure.code != harmless:
                    raise
        if self._setup_drive is not None:
            await asyncio.wait([self._setup_drive], timeout=SETUP_WAIT_S)  # ended by the cancel above
            self._setup_drive = None


def _log_setup_drive(task: asyncio.Task[JSON]) -> None:
    if task.cancelled():
        log.debug("setup drive cancelled")
    elif isinstance(failure := task.exception(), RobotFailure):
        log.info("setup drive ended: %s (%s)", failure.code, failure.message)
    elif task.exception() is not None:
        log.error("setup drive failed", exc_info=task.exception())
    else:
        log.info("setup drive finished: %s", task.result())


async def start_sim_robot(
    middleware: Middleware,
    *,
    speed: float = 1.0,
    nodes: Collection[str] | None = None,
) -> SimRobot:
    """Host the sim robot's nodes (all, or those named) on a started `middleware`."""
    names = list(NODE_NAMES) if nodes is None else list(dict.fromkeys(nodes))
    unknown = [name for name in names if name not in NODE_NAMES]
    if unknown:
        raise ConfigError(f"unknown sim node(s) {', '.join(unknown)}: "
                          f"the sim nodes are {', '.join(NODE_NAMES)}")
    body = SimBody(SimClock(speed))
    robot = SimRobot(middleware, body, {name: _make_node(name, body) for name in names})
    await robot._start()
    return robot


async def run_sim_forever(
    middleware: Middleware,
    *,
    speed: float = 1.0,
    nodes: Collection[str] | None = None,
    setup: str = "",
    on_ready: Callable[[SimRobot], object] | None = None,
) -> None:
    """Run the sim robot on a started `middleware` until cancelled (for `robovoice sim`).

    `setup` (DESIGN.md section 6) is applied first; then `on_ready(robot)` is called (e.g. to
    say so on the console). Raises if a node's background work fails; withdraws the nodes
    on the way out.
    """
    robot = await start_sim_robot(middleware, speed=speed, nodes=nodes)
    try:
        if setup:
            await robot.apply_setup(setup)
        if on_ready is not None:
            on_ready(robot)
        await robot.wait()
    finally:
        await robot.stop()
