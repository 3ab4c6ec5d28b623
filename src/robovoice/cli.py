"""The `robovoice` command line: a thin dispatcher over `robovoice.commands.*`.

Each command module exposes `register(subparsers)`, adding its sub-commands with
`set_defaults(run=<function(args) -> int>)`. Logging is configured here and only here.
"""

from __future__ import annotations

import argparse
import importlib
import logging
import os
import sys
from collections.abc import Sequence

from robovoice import __version__
from robovoice.errors import RobovoiceError

# Command modules, in the order their commands appear in --help.
COMMAND_MODULES = (
    "robovoice.commands.robot",
    "robovoice.commands.sim",
    "robovoice.commands.assistant",
    "robovoice.commands.voice",
    "robovoice.commands.bench",
    "robovoice.commands.console",
    "robovoice.commands.models",
    "robovoice.commands.audit",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="robovoice",
        description="Voice assistance for mobile robots through a function-calling LLM and MCP tools.",
    )
    parser.add_argument("--version", action="version", version=f"robovoice {__version__}")
    parser.add_argument("-v", "--verbose", action="count", default=0, help="more logging (-vv: debug)")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name != name:  # a real missing dependency inside the module: show it
                raise
            continue  # that command group is not part of this build yet
        module.register(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=[logging.WARNING, logging.INFO, logging.DEBUG][min(args.verbose, 2)],
        format="%(asctime)s %(levelname)s %(name)s: %(message)s",
        stream=sys.stderr,
    )
    run = getattr(args, "run", None)
    if run is None:
        parser.print_help()
        return 2
    try:
        return int(run(args))
    except RobovoiceError as exc:
        print(f"robovoice: error: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # the reader went away (`robovoice tools | head`): not an error worth a traceback;
        # point stdout at /dev/null so the interpreter's final flush does not fail again
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141  # 128 + SIGPIPE, as a shell pipeline reports it


if __name__ == "__main__":
    sys.exit(main())
