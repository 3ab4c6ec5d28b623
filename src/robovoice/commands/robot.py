"""Robot-side commands: serve the robot's tools over MCP, list them, call one, check manifests.

    robovoice serve --robot sim [--transport stdio|http] [--host H] [--port N] [--token-file F]
                    [--audit-log F | --no-audit-log] [--sim-speed X]
    robovoice serve --middleware URI [--manifests DIR] ...
    robovoice tools --robot sim [--json]
    robovoice call --robot sim TOOL [key=value ...] [--json]
    robovoice check-manifests DIR [--robot sim | --middleware URI]

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
from mcp import Client

from robovoice.errors import ConfigError
from robovoice.manifest import check_manifest_dir
from robovoice.mcp_server import (
    Robot,
    RobotSpec,
    check_bind,
    default_audit_path,
    http_server,
    open_robot,
    read_token_file,
    serve_stdio,
    wait_for_snapshots,
    wait_for_tools,
)
from robovoice.middleware import open_middleware
from robovoice.sim import start_sim_robot

DEFAULT_PORT = 8765
_FIRST_SENTENCE = re.compile(r"(?<![A-Z][a-z])\.\s")
DEFAULT_WAIT_S = 3.0
SNAPSHOT_WAIT_S = 5.0  # `call` of a snapshot tool right after start-up waits for the first message


# --- arguments ---------------------------------------------------------------------------


def _add_robot_args(parser: argparse.ArgumentParser, *, required: bool = True) -> None:
    where = parser.add_mutually_exclusive_group(required=required)
    where.add_argument("--robot", choices=["sim"], help="run the simulated robot in this process")
    where.add_argument("--middleware", metavar="URI",
                       help="serve the nodes present on this middleware (memory://, zenoh://host:port)")
    parser.add_argument("--manifests", type=Path, metavar="DIR",
                        help="manifests that replace the nodes' own (DIR/<node>/mcp.json or DIR/<node>.mcp.json)")
    parser.add_argument("--sim-speed", type=float, default=1.0, metavar="X",
                        help="simulated seconds per real second (default 1)")
    parser.add_argument("--wait", type=float, default=None, metavar="S",
                        help=f"with --middleware: how long to wait for the nodes to announce themselves "
                             f"(default {DEFAULT_WAIT_S:g} s)")


def _add_audit_args(parser: argparse.ArgumentParser) -> None:
    audit = parser.add_mutually_exclusive_group()
    audit.add_argument("--audit-log", type=Path, metavar="F",
                       help="append every tool call to this JSON Lines file (default: audit.jsonl in the state "
                            "dir, ~/.local/state/robovoice)")
    audit.add_argument("--no-audit-log", action="store_true", help="keep no audit log")


def register(subparsers: Any) -> None:  # argparse's _SubParsersAction is private
    serve = subparsers.add_parser(
        "serve", help="serve the robot's tools over MCP (stdio or streamable HTTP)",
        description="Serve the tools declared by the manifests of the nodes present as an MCP server.")
    _add_robot_args(serve)
    serve.add_argument("--transport", choices=["stdio", "http"], default="stdio", help="default: stdio")
    serve.add_argument("--host", default="127.0.0.1",
                       help="HTTP bind address (default 127.0.0.1; any other needs --token-file)")
    serve.add_argument("--port", type=int, default=DEFAULT_PORT, help=f"HTTP port (default {DEFAULT_PORT}; 0: any)")
    serve.add_argument("--token-file", type=Path, metavar="F",
                       help="HTTP: require 'Authorization: Bearer <the token in F>'")
    serve.add_argument("--allow-host", action="append", default=[], metavar="NAME",
                       help="HTTP: also accept this Host/Origin name, e.g. robot.local (repeatable; loopback "
                            "names and --host always are; a 0.0.0.0 bind with a token accepts any Host)")
    _add_audit_args(serve)
    serve.set_defaults(run=run_serve)

    tools = subparsers.add_parser("tools", help="list the robot's MCP tools",
                                  description="List the MCP tools the robot offers now.")
    _add_robot_args(tools)
    tools.add_argument("--json", action="store_true", help="the tool objects exactly as tools/list returns them")
    tools.set_defaults(run=run_tools)

    call = subparsers.add_parser(
        "call", help="call one of the robot's MCP tools",
        description="Call a tool through MCP. Values are JSON when they parse as JSON (on=true, n=3), "
                    "else strings (target=kitchen). Exit status 1 when the tool reports an error.")
    _add_robot_args(call)
    call.add_argument("tool", help="the tool name (see 'robovoice tools')")
    call.add_argument("arguments", nargs="*", metavar="key=value", help="the tool's arguments")
    call.add_argument("--json", action="store_true", help="print the MCP CallToolResult as JSON")
    _add_audit_args(call)
    call.set_defaults(run=run_call)

    check = subparsers.add_parser(
        "check-manifests", help="check a folder of manifests (optionally against live nodes)",
        description="Check every manifest in DIR; with --robot sim or --middleware URI also check the RPCs, "
                    "parameters and topics they name against the nodes present. Exit status 1 on errors.")
    check.add_argument("dir", type=Path, metavar="DIR")
    where = check.add_mutually_exclusive_group()
    where.add_argument("--robot", choices=["sim"], help="check against the simulated robot's nodes")
    where.add_argument("--middleware", metavar="URI", help="check against the nodes present on this middleware")
    check.add_argument("--wait", type=float, default=None, metavar="S",
                       help=f"with --middleware: time for the nodes to announce themselves "
                            f"(default {DEFAULT_WAIT_S:g} s)")
    check.set_defaults(run=run_check)


def _spec(args: argparse.Namespace, *, audit: bool) -> RobotSpec:
    if not args.sim_speed > 0:
        raise ConfigError("--sim-speed must be positive")
    audit_log: Path | None = None
    if audit and not getattr(args, "no_audit_log", False):
        audit_log = getattr(args, "audit_log", None) or default_audit_path()
    return RobotSpec(sim=args.robot == "sim", middleware_uri=args.middleware, manifests=args.manifests,
                     sim_speed=args.sim_speed, audit_log=audit_log)


def _wait_s(args: argparse.Namespace) -> float:
    if args.wait is not None:
        return max(0.0, float(args.wait))
    return DEFAULT_WAIT_S if args.middleware else 0.0


def parse_arguments(pairs: Sequence[str]) -> dict[str, Any]:
    """``key=value`` pairs → arguments; a value is JSON when it parses as JSON, else a string."""
    out: dict[str, Any] = {}
    for pair in pairs:
        key, sep, text = pair.partition("=")
        if not sep or not key:
            raise ConfigError(f"expected key=value, got {pair!r} (e.g. target=kitchen, on=true)")
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
async def _robot(args: argparse.Namespace, *, audit: bool) -> AsyncIterator[Robot]:
    async with open_robot(_spec(args, audit=audit)) as robot:
        wait = _wait_s(args)
        if wait > 0:
            names = [args.tool] if getattr(args, "tool", None) else []
            await wait_for_tools(robot.server, names=names, timeout=wait)
        yield robot


def _client(robot: Robot, name: str) -> Client:
    return Client(robot.server.server, mode="legacy", cache=None,
                  client_info=types.Implementation(name=f"robovoice-{name}", version="cli"))


def _dump(model: Any) -> Any:
    return model.model_dump(by_alias=True, mode="json", exclude_none=True)


def _print_manifest_errors(robot: Robot, out: TextIO) -> None:
    from robovoice.manifest import format_error

    for error in robot.server.catalog.errors():
        print(f"warning: {format_error(error)}", file=out)


# serve ------------------------------------------------------------------------------------


def run_serve(args: argparse.Namespace) -> int:
    token = read_token_file(args.token_file) if args.token_file else None
    if args.transport == "http":
        check_bind(args.host, token)  # before starting anything
    elif token is not None:
        raise ConfigError("--token-file applies to --transport http only")
    return _run(lambda stop: _serve(args, token, stop), graceful=True)


async def _serve(args: argparse.Namespace, token: str | None, stop: asyncio.Event) -> int:
    async with _robot(args, audit=True) as robot:
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
    return _run(lambda stop: _tools(args))


async def _tools(args: argparse.Namespace) -> int:
    async with _robot(args, audit=False) as robot, _client(robot, "tools") as client:
        listing = await client.list_tools()
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
        _print_manifest_errors(robot, sys.stderr)
    return 0


# call -------------------------------------------------------------------------------------


def run_call(args: argparse.Namespace) -> int:
    arguments = parse_arguments(args.arguments)
    return _run(lambda stop: _call(args, arguments))


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


async def _call(args: argparse.Namespace, arguments: dict[str, Any]) -> int:
    async with _robot(args, audit=True) as robot, _client(robot, "call") as client:
        await wait_for_snapshots(robot.server, names=[args.tool], timeout=SNAPSHOT_WAIT_S)
        progress_out = sys.stderr

        async def show_progress(progress: float, total: float | None, message: str | None) -> None:
            of = f"/{total:g}" if total is not None else ""
            print(f"progress {progress:g}{of}{': ' + message if message else ''}", file=progress_out, flush=True)

        result = await client.call_tool(args.tool, arguments, progress_callback=show_progress)
        print(json.dumps(_dump(result), indent=2, ensure_ascii=False) if args.json else _describe(result))
    return 1 if result.is_error else 0


# check-manifests --------------------------------------------------------------------------


def run_check(args: argparse.Namespace) -> int:
    return _run(lambda stop: _check(args))


async def _check(args: argparse.Namespace) -> int:
    if args.robot == "sim" or args.middleware:
        middleware = open_middleware(args.middleware or "memory://")
        await middleware.start()
        try:
            sim = await start_sim_robot(middleware) if args.robot == "sim" else None
            try:
                if args.middleware:
                    await _wait_for_nodes(middleware, _wait_s(args))
                report = check_manifest_dir(args.dir, dict(middleware.nodes()))
            finally:
                if sim is not None:
                    await sim.stop()
        finally:
            await middleware.close()
    else:
        report = check_manifest_dir(args.dir)
    for line in report.lines():
        print(line)
    return 0 if report.ok else 1


async def _wait_for_nodes(middleware: Any, timeout: float) -> None:
    """Give the nodes on a network middleware `timeout` s to announce themselves (until quiet)."""
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
