"""`robovoice console`: the robot console in the browser (docs/console.md).

    robovoice console                                  # the embedded sim robot, http://127.0.0.1:8780/
    robovoice console --robot http://robot:8765/mcp --robot-token-file robot.token
    robovoice console --host 0.0.0.0 --token-file console.token   # reachable from other machines
"""

from __future__ import annotations

import argparse
import asyncio
import sys
from pathlib import Path
from typing import Any

from robovoice.commands.common import (
    add_llm_args,
    add_robot_args,
    backend_from_args,
    config_from_args,
    host_name,
    port_number,
    robot_config_from_args,
    warm_up,
)
from robovoice.commands.signals import CancelOnSignals
from robovoice.config import Config
from robovoice.errors import ConfigError

DEFAULT_PORT = 8780


def register(subparsers: Any) -> None:  # argparse's _SubParsersAction is private
    console = subparsers.add_parser(
        "console", help="the robot console in the browser: watch, talk, call tools by hand",
        description="Serves one page: the robot live on its map, the conversation with every tool call, "
                    "talking through the browser's microphone, tools by hand, the audit log; and its API "
                    "(docs/console.md). Same security as `serve --transport http`.")
    add_robot_args(console, token_file=False)
    console.add_argument("--robot-token-file", type=Path, metavar="F", dest="robot_token_file",
                         help="the bearer token of an http(s):// robot address")
    web = console.add_argument_group("the page")
    web.add_argument("--host", type=host_name, default="127.0.0.1",
                     help="bind address (default 127.0.0.1: this machine only; any other needs --token-file)")
    web.add_argument("--port", type=port_number, default=DEFAULT_PORT,
                     help=f"port (default {DEFAULT_PORT}; 0: any free port)")
    web.add_argument("--token-file", type=Path, metavar="F",
                     help="require this bearer token on the page, the API and the WebSockets (a browser signs "
                          "in once at /login)")
    web.add_argument("--allow-host", action="append", default=[], type=host_name, metavar="NAME",
                     help="also accept this Host/Origin name, e.g. robot.local (repeatable)")
    web.add_argument("--no-voice", action="store_true", help="no microphone or speech (no voice models loaded)")
    add_llm_args(console)
    console.set_defaults(run=run_console_command)


def run_console_command(args: argparse.Namespace) -> int:
    return asyncio.run(_console(args))


async def _console(args: argparse.Namespace) -> int:
    from robovoice.assistant.connect import connect_robot
    from robovoice.console.serve import check_console_bind, console_server
    from robovoice.console.service import Console
    from robovoice.mcp_server.http import read_token_file

    config = config_from_args(args)
    token = read_token_file(args.token_file) if args.token_file else None
    check_console_bind(args.host, token)  # before anything is loaded
    robot = robot_config_from_args(args, config)
    backend = backend_from_args(args, config)
    try:
        async with connect_robot(robot) as connection:
            voice = None if args.no_voice else _voice_bridge(config, backend, connection.tools)
            console = Console(connection.tools, backend, voice=voice, robot_name=robot.address)
            await warm_up(backend, await connection.tools.specs())
            async with console_server(console, host=args.host, port=args.port, token=token,
                                      allowed_hosts=args.allow_host) as endpoint:
                print(f"robovoice console: {endpoint.url}  (robot {robot.address}, model {backend.name}"
                      f"{', voice models loading' if voice else ', no voice'}; Ctrl-C to end)", file=sys.stderr,
                      flush=True)
                with CancelOnSignals():
                    await console.run()
    finally:
        await backend.aclose()
    return 0


def _voice_bridge(config: Config, backend: Any, tools: Any) -> Any:
    from robovoice.console.voice import VoiceBridge

    try:
        from robovoice.voice.models import load_voice_models
    except ImportError as exc:
        raise ConfigError(f"the console's voice needs the voice extra (pip install 'robovoice[voice]'), "
                          f"or run it with --no-voice ({exc})") from exc
    voice = config.voice
    return VoiceBridge(lambda: load_voice_models(wake_model=voice.wake_model, stt=voice.stt,
                                                         wake_phases=voice.wake_phases), backend, tools)
