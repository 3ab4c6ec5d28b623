"""`robovoice sim`: run the simulated robot's nodes on a middleware until stopped.

    robovoice sim --middleware zenoh://127.0.0.1:7447 [--node navigation --node base] [--speed 5]

Prints one line on standard output once every node is hosted and announced
(``robovoice sim: ready: <nodes> on <uri>``); SIGINT or SIGTERM withdraws the nodes, closes
the middleware and exits with status 0.
"""

from __future__ import annotations

import argparse
import asyncio
from typing import Any

from robovoice.address import parse_middleware_uri
from robovoice.commands.common import positive_float
from robovoice.commands.signals import CancelOnSignals
from robovoice.errors import ConfigError
from robovoice.middleware import open_middleware
from robovoice.sim import NODE_NAMES, SETUP_NAMES, SimRobot, run_sim_forever


def register(subparsers: Any) -> None:  # argparse's _SubParsersAction is private
    parser: argparse.ArgumentParser = subparsers.add_parser(
        "sim",
        help="run the simulated robot's nodes on a middleware",
        description="Run the simulated co-presence robot (all its nodes, or the ones named) on a "
                    "middleware until SIGINT/SIGTERM. Prints one 'ready' line when the nodes are up.",
    )
    parser.add_argument("--middleware", default="zenoh://", metavar="URI",
                        help="middleware URI (default: zenoh://, peer mode on 127.0.0.1:7447; zenoh://HOST:PORT "
                             "or zenoh://tcp/HOST:PORT; see docs/zenoh.md)")
    parser.add_argument("--node", action="append", dest="nodes", choices=NODE_NAMES, metavar="NAME",
                        help=f"run only this node (repeatable): {', '.join(NODE_NAMES)}")
    parser.add_argument("--speed", type=positive_float, default=1.0,
                        help="simulated seconds per real second (default 1)")
    parser.add_argument("--setup", default="",
                        help=f"state to establish first: {', '.join(SETUP_NAMES)}, combined with '+'")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    address = parse_middleware_uri(args.middleware, "--middleware")  # a bad URI fails here, before anything starts
    if address.scheme == "memory":
        raise ConfigError("--middleware memory:// is this process's own bus, which no other process can reach; "
                          "give a network middleware (zenoh://HOST:PORT), or use --robot sim:// in the command "
                          "that should see the simulated robot")
    uri = address.uri
    unknown = [part for part in args.setup.split("+") if part and part not in SETUP_NAMES]
    if unknown or args.setup.strip("+") != args.setup or "++" in args.setup:
        raise ConfigError(f"--setup {args.setup!r}: known setups are {', '.join(SETUP_NAMES)}, combined with '+'")
    return asyncio.run(_serve(uri, args.nodes, args.speed, args.setup))


async def _serve(uri: str, nodes: list[str] | None, speed: float, setup: str) -> int:
    def ready(robot: SimRobot) -> None:
        print(f"robovoice sim: ready: {', '.join(robot.node_names)} on {uri}", flush=True)

    middleware = open_middleware(uri)
    with CancelOnSignals():
        try:
            await middleware.start()
            await run_sim_forever(middleware, speed=speed, nodes=nodes, setup=setup, on_ready=ready)
        finally:
            await middleware.close()
    return 0
