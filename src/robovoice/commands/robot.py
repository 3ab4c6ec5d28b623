"""Robot-side commands: serve the robot's tools over MCP, list them, call one, check manifests.

    robovoice serve [--robot ADDRESS | --middleware URI] [--manifests DIR] [--transport stdio|http]
                    [--host H] [--port N] [--token-file F] [--audit-log F | --no-audit-log]
    robovoice tools [--robot ADDRESS] [--json]
    robovoice call [--robot ADDRESS] TOOL [key=value ...] [--json]
    robovoice check-manifests DIR [--robot sim:// | --middleware URI]

ADDRESS is any robot address (`robovoice.address`): ``sim`` / ``sim://?speed=2`` (default),
a middleware URI (``zenoh://127.0.0.1:7447``: the nodes present there), and for `tools` and
`call` also a running MCP server (``http://host:8765/mcp``, ``stdio:COMMAND``). `serve` and
`check-manifests` need the nodes in this process: sim:// or a middleware URI.

`serve --transport http` prints one line on standard output when it is listening
(``robovoice serve: ready: http://127.0.0.1:8765/mcp (12 tools)``); over stdio nothing but
MCP goes to standard output. `tools --json` prints the tool objects exactly as ``tools/list``
returns them; `call --json` the ``CallToolResult``; `call` exits 1 when the result is an error.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import re
import signal
import sys
from collections.abc import AsyncIterator, Awaitable, Callable, Sequence
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any, TextIO

import mcp_types as types

from robovoice.address import LocalAddress, MiddlewareAddress, RobotAddress, SimAddress
from robovoice.assistant.connect import DISCOVERY_WAIT_S, RobotConnection, connect_robot, discovery_wait_s
from robovoice.commands.common import (
    add_robot_args,
    address_from_args,
    config_from_args,
    host_name,
    non_negative_float,
    port_number,
    positive_float,
    positive_int,
    robot_config_from_args,
)
from robovoice.config import RobotConfig
from robovoice.errors import ConfigError
from robovoice.manifest import check_manifest_dir
from robovoice.mcp_server import (
    RobotSide,
    check_bind,
    default_audit_path,
    http_server,
    open_robot_side,
    read_token_file,
    serve_stdio,
    wait_for_snapshots,
    wait_for_tools,
)
from robovoice.mcp_server.audit import DEFAULT_KEEP, DEFAULT_MAX_BYTES, AuditLog

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8765
_FIRST_SENTENCE = re.compile(r"(?<![A-Z][a-z])\.\s")
SNAPSHOT_WAIT_S = 5.0  # `call` of a snapshot tool right after start-up waits for the first message


# --- arguments ---------------------------------------------------------------------------


def _add_wait_arg(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--wait", type=non_negative_float, default=None, metavar="S",
                        help=f"with a middleware URI: how long to wait for the nodes to announce themselves "
                             f"(default {DISCOVERY_WAIT_S:g} s)")


def _add_audit_args(parser: argparse.ArgumentParser) -> None:
    audit = parser.add_mutually_exclusive_group()
    audit.add_argument("--audit-log", type=Path, metavar="F",
                       help="append every tool call to this JSON Lines file (default: audit.jsonl in the state "
                            "dir, ~/.local/state/robovoice)")
    audit.add_argument("--no-audit-log", action="store_true", help="keep no audit log")
    parser.add_argument("--audit-max-mb", type=positive_float, default=DEFAULT_MAX_BYTES / 2**20, metavar="MB",
                        help="rotate the audit log past this size: F -> F.1 -> F.2 ... (default 16)")
    parser.add_argument("--audit-keep", type=positive_int, default=DEFAULT_KEEP, metavar="N",
                        help="rotated audit files kept (default 5)")


def register(subparsers: Any) -> None:  # argparse's _SubParsersAction is private
    serve = subparsers.add_parser(
        "serve", help="serve the robot's tools over MCP (stdio or streamable HTTP)",
        description="Serve the tools declared by the manifests of the nodes present as an MCP server.")
    add_robot_args(serve, token_file=False, config=True)
    _add_wait_arg(serve)
    serve.add_argument("--transport", choices=["stdio", "http"], default="stdio", help="default: stdio")
    serve.add_argument("--host", type=host_name, default=None,
                       help="HTTP bind address (default 127.0.0.1; any other needs --token-file)")
    serve.add_argument("--port", type=port_number, default=None,
                       help=f"HTTP port (default {DEFAULT_PORT}; 0: any free port)")
    serve.add_argument("--token-file", type=Path, metavar="F",
                       help="HTTP: require 'Authorization: Bearer <the token in F>'")
    serve.add_argument("--allow-host", action="append", default=[], type=host_name, metavar="NAME",
                       help="HTTP: also accept this Host/Origin name, e.g. robot.local (repeatable; loopback "
                            "names and --host always are; a 0.0.0.0 bind with a token accepts any Host)")
    _add_audit_args(serve)
    serve.set_defaults(run=run_serve)

    tools = subparsers.add_parser("tools", help="list the robot's MCP tools",
                                  description="List the MCP tools the robot offers now.")
    add_robot_args(tools, config=True)
    _add_wait_arg(tools)
    tools.add_argument("--json", action="store_true", help="the tool objects exactly as tools/list returns them")
    tools.set_defaults(run=run_tools)

    call = subparsers.add_parser(
        "call", help="call one of the robot's MCP tools",
        description="Call a tool through MCP. Values are JSON when they parse as JSON (on=true, n=3), "
                    "else strings (target=kitchen). Exit status 1 when the tool reports an error.")
    add_robot_args(call, config=True)
    _add_wait_arg(call)
    call.add_argument("tool", help="the tool name (see 'robovoice tools')")
    call.add_argument("arguments", nargs="*", metavar="key=value", help="the tool's arguments")
    call.add_argument("--json", action="store_true", help="print the MCP CallToolResult as JSON")
    _add_audit_args(call)
    call.set_defaults(run=run_call)

    check = subparsers.add_parser(
        "check-manifests", help="check a folder of manifests (optionally against live nodes)",
        description="Check every manifest in DIR; with --robot sim:// or --middleware URI also check the RPCs, "
                    "parameters and topics they name against the nodes present. Exit status 1 on errors.")
    check.add_argument("dir", type=Path, metavar="DIR")
    where = check.add_mutually_exclusive_group()
    where.add_argument("--robot", metavar="ADDRESS",
                       help="check against this robot's nodes: sim:// or a middleware URI")
    where.add_argument("--middleware", metavar="URI", help="check against the nodes present on this middleware")
    _add_wait_arg(check)
    check.set_defaults(run=run_check)


def _robot_config(args: argparse.Namespace) -> RobotConfig:
    return robot_config_from_args(args, config_from_args(args))


def _audit_log(args: argparse.Namespace, target: RobotAddress) -> AuditLog | None:
    if getattr(args, "no_audit_log", False):
        return None
    if not isinstance(target, LocalAddress):
        if getattr(args, "audit_log", None) is not None:
            raise ConfigError(f"--audit-log applies to a robot served here; the MCP server at {target} keeps its own")
        return None
    path = getattr(args, "audit_log", None) or default_audit_path()
    return AuditLog(path, max_bytes=int(args.audit_max_mb * 2**20), keep=args.audit_keep)


def _wait_s(args: argparse.Namespace, target: RobotAddress) -> float:
    if args.wait is not None:
        if not isinstance(target, LocalAddress):
            raise ConfigError(f"--wait applies to nodes on a middleware URI; the MCP server at {target} has its "
                              f"tools already")
        return float(args.wait)
    return discovery_wait_s(target)


def parse_arguments(pairs: Sequence[str]) -> dict[str, Any]:
    """``key=value`` pairs → arguments; a value is JSON when it parses as JSON, else a string."""
    out: dict[str, Any] = {}
    for pair in pairs:
        key, sep, text = pair.partition("=")
        if not sep or not key:
            raise ConfigError(f"expected key=value, got {pair!r} (e.g. target=kitchen, on=true)")
        if key in out:
            raise ConfigError(f"argument {key!r} given twice ({pair!r}); give each argument once")
        try:
            out[key] = json.loads(text)
        except ValueError:
            out[key] = text
    return out


# --- running -----------------------------------------------------------------------------


_SIGNALS = (signal.SIGINT, signal.SIGTERM)


def _run(main: Callable[[asyncio.Event], Awaitable[int]], *, graceful: bool = False) -> int:
    """Run `main(stop)`, the robot always shut down on the way out. On SIGINT/SIGTERM a
    `graceful` command (serve) sees `stop` set and ends by itself; otherwise, or on a second
    signal, it is cancelled (exit status 130)."""

    async def guarded() -> int:
        loop = asyncio.get_running_loop()
        task = asyncio.current_task()
        assert task is not None
        stop = asyncio.Event()

        def on_signal() -> None:
            if graceful and not stop.is_set():
                stop.set()
            else:
                task.cancel()

        for signum in _SIGNALS:
            loop.add_signal_handler(signum, on_signal)
        try:
            return await main(stop)
        except asyncio.CancelledError:
            return 130
        finally:
            for signum in _SIGNALS:
                loop.remove_signal_handler(signum)

    return asyncio.run(guarded())


@asynccontextmanager
async def _robot_side(args: argparse.Namespace, config: RobotConfig) -> AsyncIterator[RobotSide]:
    address = config.local(f"robovoice {args.command}")
    async with open_robot_side(address, manifests=config.manifests, audit_log=_audit_log(args, address)) as side:
        wait = _wait_s(args, address)
        if wait > 0:
            await wait_for_tools(side.server, timeout=wait)
        yield side


@asynccontextmanager
async def _connection(args: argparse.Namespace, config: RobotConfig) -> AsyncIterator[RobotConnection]:
    target = config.target()
    names = [args.tool] if getattr(args, "tool", None) else []
    async with connect_robot(config, audit_log=_audit_log(args, target), settle_s=_wait_s(args, target),
                             tool_names=names, client_name=f"robovoice-{args.command}") as robot:
        yield robot


def _dump(model: Any) -> Any:
    return model.model_dump(by_alias=True, mode="json", exclude_none=True)


def _print_manifest_errors(side: RobotSide | None, out: TextIO) -> None:
    from robovoice.manifest import format_error

    if side is None:
        return
    for error in side.server.catalog.errors():
        print(f"warning: {format_error(error)}", file=out)


# serve ------------------------------------------------------------------------------------


def run_serve(args: argparse.Namespace) -> int:
    config = _robot_config(args)
    config.local("robovoice serve")  # before anything starts
    if args.transport != "http":
        given = [flag for flag, value in (("--host", args.host), ("--port", args.port),
                                          ("--allow-host", args.allow_host), ("--token-file", args.token_file))
                 if value not in (None, [])]
        if given:
            raise ConfigError(f"{', '.join(given)} appl{'ies' if len(given) == 1 else 'y'} to --transport http only")
    args.host = args.host or DEFAULT_HOST
    args.port = DEFAULT_PORT if args.port is None else args.port
    token = read_token_file(args.token_file) if args.token_file else None
    if args.transport == "http":
        check_bind(args.host, token)  # before starting anything
    return _run(lambda stop: _serve(args, config, token, stop), graceful=True)


async def _serve(args: argparse.Namespace, config: RobotConfig, token: str | None, stop: asyncio.Event) -> int:
    async with _robot_side(args, config) as robot:
        _print_manifest_errors(robot, sys.stderr)
        if args.transport == "stdio":
            async with asyncio.TaskGroup() as group:  # until the client closes stdin, or a signal
                serving = group.create_task(serve_stdio(robot.server))
                stopping = group.create_task(stop.wait())
                await asyncio.wait({serving, stopping}, return_when=asyncio.FIRST_COMPLETED)
                serving.cancel()
                stopping.cancel()
            return 0
        async with http_server(robot.server, host=args.host, port=args.port, token=token,
                               allowed_hosts=args.allow_host) as endpoint:
            print(f"robovoice serve: ready: {endpoint.url} ({len(robot.server.tools())} tools)", flush=True)
            await stop.wait()
    return 0


# tools ------------------------------------------------------------------------------------


def run_tools(args: argparse.Namespace) -> int:
    args.no_audit_log = True  # listing calls no tool
    config = _robot_config(args)
    return _run(lambda stop: _tools(args, config))


async def _tools(args: argparse.Namespace, config: RobotConfig) -> int:
    async with _connection(args, config) as robot:
        listing = await robot.tools.client.list_tools()
        if args.json:
            print(json.dumps([_dump(tool) for tool in listing.tools], indent=2, ensure_ascii=False))
        else:
            width = max((len(tool.name) for tool in listing.tools), default=0)
            for tool in listing.tools:
                params = ", ".join(tool.input_schema.get("properties", {}))
                first = _FIRST_SENTENCE.split(tool.description or "", maxsplit=1)[0].rstrip(".")
                print(f"{tool.name:<{width}}  ({params})  {first}")
            if not listing.tools:
                print("no tools: no node with a manifest is present", file=sys.stderr)
        _print_manifest_errors(robot.side, sys.stderr)
    return 0


# call -------------------------------------------------------------------------------------


def run_call(args: argparse.Namespace) -> int:
    arguments = parse_arguments(args.arguments)
    config = _robot_config(args)
    return _run(lambda stop: _call(args, config, arguments))


def _describe(result: types.CallToolResult) -> str:
    lines: list[str] = []
    for block in result.content:
        if isinstance(block, types.TextContent):
            lines.append(block.text)
        elif isinstance(block, types.ImageContent):
            lines.append(f"[image {block.mime_type}, {len(block.data) * 3 // 4} bytes]")
        else:
            lines.append(json.dumps(_dump(block)))
    return "\n".join(lines)


async def _call(args: argparse.Namespace, config: RobotConfig, arguments: dict[str, Any]) -> int:
    async with _connection(args, config) as robot:
        client = robot.tools.client
        if robot.side is not None:
            await wait_for_snapshots(robot.side.server, names=[args.tool], timeout=SNAPSHOT_WAIT_S)
        progress_out = sys.stderr

        async def show_progress(progress: float, total: float | None, message: str | None) -> None:
            of = f"/{total:g}" if total is not None else ""
            print(f"progress {progress:g}{of}{': ' + message if message else ''}", file=progress_out, flush=True)

        result = await client.call_tool(args.tool, arguments, progress_callback=show_progress)
        print(json.dumps(_dump(result), indent=2, ensure_ascii=False) if args.json else _describe(result))
    return 1 if result.is_error else 0


# check-manifests --------------------------------------------------------------------------


def run_check(args: argparse.Namespace) -> int:
    address = address_from_args(args)
    if address is not None and not isinstance(address, LocalAddress):
        raise ConfigError(f"check-manifests checks against the nodes themselves: give sim:// or a middleware URI, "
                          f"not {address}")
    return _run(lambda stop: _check(args, address))


async def _check(args: argparse.Namespace, address: LocalAddress | None) -> int:
    if address is None:
        report = check_manifest_dir(args.dir)
    else:
        if isinstance(address, SimAddress):
            address = SimAddress(None, address.nodes)  # speed does not matter here
        async with open_robot_side(address, manifests=None, audit_log=None) as side:
            if isinstance(address, MiddlewareAddress):
                await _wait_for_nodes(side, _wait_s(args, address))
            report = check_manifest_dir(args.dir, dict(side.middleware.nodes()))
    for line in report.lines():
        print(line)
    return 0 if report.ok else 1


async def _wait_for_nodes(side: RobotSide, timeout: float) -> None:
    """Give the nodes on a network middleware `timeout` s to announce themselves (until quiet)."""
    middleware = side.middleware
    changed = asyncio.Event()
    watch = await middleware.watch(lambda event: changed.set())
    try:
        async with asyncio.timeout(timeout):
            while True:
                changed.clear()
                await asyncio.wait_for(changed.wait(), timeout=0.3 if middleware.nodes() else timeout)
    except TimeoutError:
        pass
    finally:
        watch.close()
