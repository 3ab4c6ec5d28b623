"""`robovoice bench soak`: load the shipped voice models and the embedded model, run the soak,
print a summary (or the whole report as JSON) and optionally write the memory plot."""

from __future__ import annotations

import asyncio
import json
import logging
import signal
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from robovoice.soak import SoakReport, SoakSettings, run_soak, write_memory_plot

log = logging.getLogger(__name__)


async def soak_with_embedded_model(settings: SoakSettings, ending: asyncio.Event | None = None) -> SoakReport:
    from robovoice.assistant.prompt import SYSTEM_PROMPT
    from robovoice.llm.base import ToolSpec
    from robovoice.llm.local import LocalLlamaBackend
    from robovoice.voice.models import load_voice_models

    models = await asyncio.to_thread(load_voice_models)
    backend = LocalLlamaBackend()

    async def warm_up(specs: Sequence[ToolSpec]) -> Any:
        return await backend.warm_up(SYSTEM_PROMPT, specs)

    try:
        return await run_soak(models, backend, settings, warm_up=warm_up, ending=ending)
    finally:
        await backend.aclose()


async def _until_signalled(settings: SoakSettings) -> SoakReport:
    """The soak; SIGINT or SIGTERM ends it early (after the command under way) with its report,
    so a long run can be read before its end."""
    ending = asyncio.Event()
    loop = asyncio.get_running_loop()

    def end(signame: str) -> None:
        log.warning("%s: the soak ends after the command under way and reports what it has", signame)
        ending.set()

    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, end, sig.name)
    try:
        return await soak_with_embedded_model(settings, ending)
    finally:
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.remove_signal_handler(sig)


def summary(report: SoakReport) -> str:
    c, m, e, lk = report.commands, report.memory, report.errors, report.leaks
    lines = [
        f"soak: {report.sim_hours:.2f} simulated h in {report.wall_s:.0f} s wall "
        f"(x{report.stream['speed_up']}; {report.stream['paced_real_time_s']:.0f} s of it paced at real time "
        f"while the assistant was busy); load {report.load_avg_1_5_15}",
        f"commands: {c['answered']}/{c['given']} answered, {c['done']}/{c['given']} done right; "
        f"barge-ins heard {c['barge_ins_heard']}; not idle within the turn timeout {c['late']}",
        *(f"  {k}: {v['answered']}/{v['given']} answered, {v['done']} done" for k, v in c["by_kind"].items()
          if v["given"]),
        *(f"  not done at {o['sim_at_s']:.0f} s: {o['said']!r}: {o['problem']}" for o in c["not_done"]),
        f"false wakes: {report.false_wakes['count']} ({report.false_wakes['per_hour']}/h); "
        f"turns outside commands {report.false_wakes['turns_outside_commands']}; "
        f"unasked actions: {report.unasked_actions['count']} {report.unasked_actions['tools']}",
        f"errors: {e['error_logs']} ERROR records, {e['warning_logs']} warnings, unhandled {len(e['unhandled'])}",
        *(f"  {line}" for line in e["first_errors"] + e["unhandled"]),
        f"memory: RSS {m['rss_mib_first_last']} MiB, growth after warm-up {m['rss_growth_pct_per_hour']} %/h; "
        f"anonymous RSS {m['rss_anon_mib_first_last']} MiB, {m['rss_anon_growth_pct_per_hour']} %/h; "
        f"heap blocks {m['heap_blocks_first_last']}, {m['heap_growth_pct_per_hour']} %/h; "
        f"gc objects {m['gc_objects_growth_pct_per_hour']} %/h; fds {m['fds_first_last']}",
        f"left behind: tasks {lk['tasks_left']} ({lk['tasks_before']} -> {lk['tasks_after']}), "
        f"threads {lk['threads_left']} ({lk['threads_before']} -> {lk['threads_after']})",
        f"goals met: {report.ok}" + (" (ended early: a partial run)" if report.settings.get("ended_early") else ""),
    ]
    return "\n".join(lines)


def run_soak_command(*, hours: float, seed: int, gap_minutes: float, sample_minutes: float, plot: Path | None,
                     as_json: bool) -> int:
    settings = SoakSettings(hours=hours, seed=seed, mean_gap_minutes=gap_minutes, sample_minutes=sample_minutes,
                            warm_up_minutes=min(15.0, hours * 60.0 / 8))
    progress = logging.getLogger("robovoice.soak")  # progress on stderr: a long run says where it is
    progress.setLevel(logging.INFO)
    progress.propagate = False
    handler = logging.StreamHandler()
    handler.setFormatter(logging.Formatter("%(asctime)s %(message)s"))
    progress.addHandler(handler)
    try:
        report = asyncio.run(_until_signalled(settings))
    finally:
        progress.removeHandler(handler)
    if plot is not None and report.samples:
        write_memory_plot(report, plot)
    print(json.dumps(report.to_dict(), indent=1) if as_json else summary(report))  # the command's output
    if plot is not None:
        print(f"memory plot: {plot}")
    return 0
