"""`robovoice chat` (a text conversation) and `robovoice eval` (case files → scores)."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import logging
import sys
import threading
import time
from collections.abc import Sequence
from pathlib import Path
from typing import TextIO

import anyio

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.events import (
    BackendFailed,
    SentenceReady,
    ToolCalled,
    ToolProgressed,
    ToolReturned,
    TurnEvent,
)
from robovoice.assistant.loop import Assistant
from robovoice.commands.common import (
    add_llm_args,
    add_robot_args,
    backend_from_args,
    config_from_args,
    positive_int,
    robot_config_from_args,
    warm_up,
)
from robovoice.commands.signals import CancelOnSignals
from robovoice.commands.text import one_line, shown_reply
from robovoice.errors import ConfigError
from robovoice.eval.cases import Case, load_cases
from robovoice.eval.runner import CaseResult, run_eval


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    chat = subparsers.add_parser(
        "chat", help="talk to the robot in text (reads lines from stdin when it is not a terminal)",
        description="A text conversation with the assistant; tool calls and results are shown as they happen.")
    add_robot_args(chat)
    add_llm_args(chat)
    chat.add_argument("--max-steps", type=positive_int, default=4, help="model calls per turn at most (default 4)")
    chat.set_defaults(run=run_chat)

    ev = subparsers.add_parser(
        "eval", help="run an evaluation case file (DESIGN.md §6) and report accuracy and latency",
        description="Runs each case with a fresh robot and conversation. Exit status 0 whatever the score. "
                    "A file with audio cases runs the sim at 2x unless --sim-speed is given.")
    ev.add_argument("file", type=Path, help="a JSON Lines case file")
    add_robot_args(ev, default_speed=10.0)
    add_llm_args(ev)
    ev.add_argument("--json", action="store_true", help="print one JSON object with the summary and every case")
    ev.add_argument("--limit", type=positive_int, help="run only the first N cases")
    ev.add_argument("--quiet", action="store_true", help="no per-case lines on stderr")
    ev.add_argument("--only", action="append", metavar="ID", help="run only these case ids")
    ev.add_argument("--record", type=Path, metavar="DIR",
                    help="audio cases: write each case's session as DIR/<id>.wav, a stereo WAV aligned with the clip "
                         "(channel 1 the microphone, channel 2 the robot; docs/voice.md, 'Recording a session')")
    ev.set_defaults(run=run_eval_command)


class ChatPrinter:
    """Prints a turn as it happens; progress lines at most once a second per tool."""

    def __init__(self, out: TextIO = sys.stdout) -> None:
        self.out = out
        self._last_progress: dict[str, float] = {}

    def __call__(self, event: TurnEvent) -> None:
        match event:
            case ToolCalled(name=name, arguments=arguments):
                args = ", ".join(f"{k}={v!r}" for k, v in arguments.items())
                print(f"  → {name}({args})", file=self.out, flush=True)
            case ToolReturned(name=name, text=text, is_error=is_error, duration_ms=ms):
                tag = "error" if is_error else "ok"
                print(f"  ← {name} {tag} ({ms:.0f} ms): {one_line(text, 160)}", file=self.out, flush=True)
            case ToolProgressed(name=name, message=message) if message:
                now = time.monotonic()
                if now - self._last_progress.get(name, 0.0) >= 1.0:
                    self._last_progress[name] = now
                    print(f"  … {message}", file=self.out, flush=True)
            case SentenceReady(text=text) if (shown := shown_reply(text)) is not None:
                print(f"robot> {shown}", file=self.out, flush=True)
            case BackendFailed(reason=reason):
                print(f"  ! no language model answered: {one_line(reason, 300)}", file=self.out, flush=True)
            case _:
                pass


async def _chat(args: argparse.Namespace) -> int:
    config = config_from_args(args)
    robot = robot_config_from_args(args, config)
    backend = backend_from_args(args, config)
    interactive = sys.stdin.isatty()
    try:
        async with connect_robot(robot) as link:
            specs = await link.tools.specs()
            if interactive:
                print(f"robovoice chat: {len(specs)} tools from {robot.describe()}; loading the model…", flush=True)
            await warm_up(backend, specs)
            assistant = Assistant(backend, link.tools, observer=ChatPrinter(), max_steps=args.max_steps)
            if interactive:
                print("Type a request (Ctrl-D to quit).", flush=True)
            while True:
                if interactive:
                    print("you> ", end="", flush=True)
                line = await _read_line()
                if not line:
                    break
                if line.strip():
                    await assistant.turn(line.strip())
    finally:
        await backend.aclose()
    return 0


async def _read_line() -> str:
    """One line of stdin, read in a daemon thread: a signal while waiting for input ends the
    command at once (`asyncio.to_thread` would make the exit wait for the next line)."""
    loop = asyncio.get_running_loop()
    future: asyncio.Future[str] = loop.create_future()

    def deliver(line: str) -> None:
        if not future.done():
            future.set_result(line)

    def read() -> None:
        line = sys.stdin.readline()
        with contextlib.suppress(RuntimeError):  # the loop has closed meanwhile
            loop.call_soon_threadsafe(deliver, line)

    threading.Thread(target=read, name="chat-stdin", daemon=True).start()
    return await future


def run_chat(args: argparse.Namespace) -> int:
    async def until_signalled() -> int:
        code = 0
        with CancelOnSignals() as stop:  # SIGTERM/SIGINT: the turn under way (and its tool call) is cancelled
            sdk_log = logging.getLogger("mcp.client.streamable_http")
            # the SDK logs a traceback when an event arrives for a stream it is closing: not news after a signal
            sdk_log.addFilter(lambda r: not (stop.signalled and r.exc_info
                                             and r.exc_info[0] is anyio.BrokenResourceError))
            code = await _chat(args)
        if stop.signalled:
            print("robovoice chat: stopped by a signal; the turn under way was cancelled, and with it any "
                  "robot action it had started", file=sys.stderr, flush=True)
        return code

    return asyncio.run(until_signalled())


def _print_case(result: CaseResult) -> None:
    mark = "PASS" if result.passed else "FAIL"
    latency = result.latency_ms.get("first_sentence")
    ms = f"{latency:7.0f} ms" if latency is not None else "      - ms"
    calls = ", ".join(c["tool"] for c in result.calls) or "-"
    print(f"{mark} {result.id:<20} {ms}  calls: {calls}" + ("" if result.passed else f"  ({result.reason})"),
          file=sys.stderr, flush=True)


AUDIO_SIM_SPEED = 2.0


def eval_sim_speed(cases: Sequence[Case], default: float) -> float:
    """The sim's speed when --sim-speed is not given: audio cases play in real time, and at 10x
    the "driving" setup's drive reaches its place (about 2 s) before a spoken stop is over."""
    return AUDIO_SIM_SPEED if any(c.audio is not None for c in cases) else default


async def _eval(args: argparse.Namespace) -> int:
    cases = load_cases(args.file)
    if args.only:
        unknown = sorted(set(args.only) - {c.id for c in cases})
        if unknown:
            raise ConfigError(f"--only: no case with id {', '.join(map(repr, unknown))} in {args.file}")
        cases = [c for c in cases if c.id in set(args.only)]
    if args.limit:
        cases = cases[: args.limit]
    if args.record is not None and not args.record.is_dir():
        raise ConfigError(f"--record {args.record}: no such folder; create it first")
    config = config_from_args(args)
    args.default_sim_speed = eval_sim_speed(cases, args.default_sim_speed)
    robot = robot_config_from_args(args, config)
    backend = backend_from_args(args, config)
    audio = None
    try:
        async with connect_robot(robot) as link:  # once, to warm the model with the real tool list
            await warm_up(backend, await link.tools.specs())
        if any(c.audio is not None for c in cases):
            from robovoice.voice.evaluation import open_clip_runner  # needs robovoice[voice]

            async with open_clip_runner(config, record_dir=args.record) as audio:
                report = await run_eval(cases, backend, lambda: connect_robot(robot), audio=audio,
                                        on_result=None if args.quiet else _print_case)
        else:
            report = await run_eval(cases, backend, lambda: connect_robot(robot),
                                    on_result=None if args.quiet else _print_case)
    finally:
        await backend.aclose()
    summary = report.to_dict()
    if args.json:
        print(json.dumps(summary, indent=None))
    else:
        print(f"{summary['passed']}/{summary['cases']} passed ({summary['accuracy']:.1%}); "
              f"input (end-of-turn decision, or text) → first sentence p50 {summary['p50']} ms, "
              f"p95 {summary['p95']} ms; backend {summary['backend']}")
        for stage, figures in summary["stages"].items():
            print(f"  {stage:<16} p50 {figures['p50']:>8} ms   p95 {figures['p95']:>8} ms   (n={figures['n']})")
        spoken = summary["speech_end_to_first_audio"]
        if spoken is not None:  # audio cases: from the user's last word, not the end-of-turn decision
            print(f"from the last word: first audio p50 {spoken['p50']} ms, p95 {spoken['p95']} ms (n={spoken['n']})")
            for stage, figures in summary["stages_from_speech_end"].items():
                print(f"  {stage:<16} p50 {figures['p50']:>8} ms   p95 {figures['p95']:>8} ms   (n={figures['n']})")
    return 0


def run_eval_command(args: argparse.Namespace) -> int:
    return asyncio.run(_eval(args))
