"""`robovoice bench …`: the benchmarks whose figures go into docs/performance.md.

Each prints JSON (machine-readable, pasted into the docs) — or a table where the benchmark
has one — and exits 0. Benchmarks are measurements, not tests: nothing here asserts a goal.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import os
import platform
from dataclasses import asdict, is_dataclass
from pathlib import Path
from typing import Any

from robovoice.commands.common import existing_file, positive_float, positive_int


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    bench = subparsers.add_parser("bench", help="run a benchmark (figures for docs/performance.md)")
    sub = bench.add_subparsers(dest="bench_command", metavar="BENCH", required=True)

    mcp = sub.add_parser("mcp", help="MCP tool-call latency in-process / stdio / HTTP vs a plain SDK server; "
                                     "snapshot reads; snapshot ingest at 1 and 10 kHz")
    mcp.add_argument("-n", type=positive_int, default=300, help="calls per transport (default 300)")
    mcp.set_defaults(run=_mcp)

    zenoh = sub.add_parser("zenoh", help="RPC round trip over Zenoh vs a bare get(); MCP over Zenoh vs memory; "
                                         "snapshot ingest from another process")
    zenoh.add_argument("-n", type=positive_int, default=1000, help="RPC calls (default 1000)")
    zenoh.set_defaults(run=_zenoh)

    ros2 = sub.add_parser("ros2", help="MCP tool call over ROS 2 vs a bare rclpy client on the same service; "
                                       "30 Hz image ingest and memory; time to notice a killed node")
    ros2.add_argument("--rounds", type=positive_int, default=6, help="interleaved rounds of 50 calls (default 6)")
    ros2.add_argument("--domain", type=int, default=231, help="ROS_DOMAIN_ID to run on (default 231)")
    ros2.set_defaults(run=_ros2)

    llm = sub.add_parser("llm", help="the embedded model: load, warm-up, prefix reuse, first-event latency")
    llm.add_argument("--repeats", type=positive_int, default=1)
    llm.add_argument("--threads", type=positive_int, default=2)
    llm.set_defaults(run=_llm)

    audio = sub.add_parser("audio", help="wake word + VAD CPU, STT latency and accuracy, TTS first audio, "
                                         "wake-word false accepts")
    audio.add_argument("--fixtures", type=Path, default=Path("tests/data/audio"))
    audio.add_argument("--negative-wav", type=existing_file,
                       help="long audio without the wake phrase (≥ 10 min advised); make it with "
                            "scripts/make_audio_fixtures.py --negative-minutes")
    audio.add_argument("--repeats", type=positive_int, default=3)
    audio.set_defaults(run=_audio)

    voice = sub.add_parser("voice", help="the user's last word → first audio out, all-local, per stage (also from "
                                         "the end-of-turn decision), against the naive chain of the same models; "
                                         "or the pipeline's own overhead with instant model fakes; or spoken "
                                         "stops while the sim robot drives (last word -> the robot)")
    voice.add_argument("which", nargs="?", choices=["local", "overhead", "stops"], default="local")
    voice.add_argument("--turns", type=positive_int,
                       help="turns to measure (default: the 22 bench commands once for local, 30 overhead, "
                            "12 stops)")
    voice.add_argument("--stop-wav", type=existing_file, action="append", default=[],
                       help="stops: a recorded stop clip (repeatable; default: six stop phrases spoken by Piper)")
    voice.add_argument("--no-naive", action="store_true", help="local: skip the naive chain (no ratio)")
    voice.add_argument("--no-checks", action="store_true",
                       help="local: without the check before acting and held calls (issue 11's baseline)")
    voice.add_argument("--wake-phases", type=int, choices=[1, 2, 4, 8], default=8,
                       help="local: 10 ms offsets the wake word is scored at ([voice] wake_phases; 1: openWakeWord's)")
    voice.add_argument("--json", action="store_true", help="(the output is JSON either way)")
    voice.set_defaults(run=_voice)

    console = sub.add_parser("console", help="the console page open for minutes: page and server memory, "
                                             "responsiveness (headless chromium, the sim, a scripted model)")
    console.add_argument("--minutes", type=positive_float, default=10.0, help="how long (default 10)")
    console.set_defaults(run=_console)

    load = sub.add_parser("load", help="N concurrent MCP clients over streamable HTTP, nodes joining and leaving")
    load.add_argument("--clients", type=positive_int, default=50)
    load.add_argument("--calls", type=positive_int, default=200, help="calls per client (default 200)")
    load.add_argument("--middleware", choices=["memory", "zenoh", "ros2"], default="memory", help="where the nodes are")
    load.add_argument("--domain", type=int, default=120, help="ROS_DOMAIN_ID with --middleware ros2 (default 120)")
    load.set_defaults(run=_load)

    soak = sub.add_parser("soak", help="the whole embedded assistant hearing hours of a home (television, music, "
                                       "noise, commands) in accelerated stream time; memory, fds, threads, tasks")
    soak.add_argument("--hours", type=positive_float, default=2.0, help="simulated hours (default 2)")
    soak.add_argument("--seed", type=int, default=1, help="the script's random seed (default 1)")
    soak.add_argument("--gap-minutes", type=positive_float, default=3.0,
                      help="mean simulated minutes between commands (default 3)")
    soak.add_argument("--sample-minutes", type=positive_float, default=5.0,
                      help="simulated minutes between process samples (default 5)")
    soak.add_argument("--plot", type=Path, help="write the memory plot (PNG) here")
    soak.add_argument("--json", action="store_true", help="print the whole report as JSON, samples included")
    soak.set_defaults(run=_soak)


def _machine() -> dict[str, Any]:
    model = ""
    with contextlib.suppress(OSError, StopIteration):
        model = next(line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                     if line.startswith("model name"))
    return {"cpu": model, "cores": os.cpu_count(), "python": platform.python_version(),
            "load_avg_1m": round(os.getloadavg()[0], 2)}


def _print(result: Any) -> int:
    if is_dataclass(result) and not isinstance(result, type):
        result = asdict(result)
    elif hasattr(result, "to_dict"):
        result = result.to_dict()
    print(json.dumps({"machine": _machine(), "result": result}, indent=1, default=str))
    return 0


def _mcp(args: argparse.Namespace) -> int:
    from robovoice.mcp_server.bench import bench_mcp, format_report

    report = asyncio.run(bench_mcp(args.n))
    print(format_report(report))
    print(f"machine: {_machine()}")
    return 0


def _zenoh(args: argparse.Namespace) -> int:
    from robovoice.middleware.bench_zenoh import run_zenoh_bench

    return _print(asyncio.run(run_zenoh_bench(calls=args.n)))


def _ros2(args: argparse.Namespace) -> int:
    from robovoice.middleware.bench_ros2 import run_ros2_bench  # needs the [ros2] extra

    return _print(asyncio.run(run_ros2_bench(domain=args.domain, rounds=args.rounds)))


def _llm(args: argparse.Namespace) -> int:
    from robovoice.llm.bench import bench_local

    async def run() -> Any:
        from robovoice.llm.local import LocalLlamaBackend

        backend = LocalLlamaBackend(n_threads=args.threads)
        try:
            return await bench_local(backend, repeats=args.repeats)
        finally:
            await backend.aclose()

    return _print(asyncio.run(run()))


def _audio(args: argparse.Namespace) -> int:
    from robovoice.audio.bench import run_all
    from robovoice.errors import ConfigError

    if not args.fixtures.is_dir():
        raise ConfigError(f"--fixtures {args.fixtures}: no such folder (make it with scripts/make_audio_fixtures.py)")
    return _print(run_all(args.fixtures, negative_wav=args.negative_wav, whisper=True, repeats=args.repeats))


def _voice(args: argparse.Namespace) -> int:
    from robovoice.voice.bench import LOCAL_COMMANDS, bench_local, bench_overhead

    if args.which == "overhead":
        return _print(asyncio.run(bench_overhead(args.turns or 30)))
    if args.which == "stops":
        from robovoice.voice.bench_stops import bench_stops

        return _print(asyncio.run(bench_stops(args.turns or 12, wavs=args.stop_wav)))
    from robovoice.config import VoiceConfig

    return _print(asyncio.run(bench_local(args.turns or len(LOCAL_COMMANDS), naive=not args.no_naive,
                                          voice=VoiceConfig(wake_phases=args.wake_phases), checks=not args.no_checks)))


def _console(args: argparse.Namespace) -> int:
    from robovoice.console.bench import bench_console

    return _print(asyncio.run(bench_console(args.minutes)))


def _load(args: argparse.Namespace) -> int:
    from robovoice.mcp_server.bench_load import bench_load

    return _print(asyncio.run(bench_load(args.clients, args.calls, middleware=args.middleware,
                                         ros_domain=args.domain)))


def _soak(args: argparse.Namespace) -> int:
    from robovoice.soak.cli import run_soak_command

    return run_soak_command(hours=args.hours, seed=args.seed, gap_minutes=args.gap_minutes,
                            sample_minutes=args.sample_minutes, plot=args.plot, as_json=args.json)
