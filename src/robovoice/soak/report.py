"""The soak's figures: commands answered and done, false wakes, unasked actions, errors,
and the process samples with their growth after warm-up; `SoakReport.ok` against the goals
of issue 14 (memory growth < 2 % per simulated hour, nothing unasked, nothing unhandled,
no task or thread left behind)."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

from robovoice.soak.probe import Sample, growth_per_hour
from robovoice.soak.script import KINDS, Outcome

MAX_GROWTH_PCT_PER_HOUR = 2.0


@dataclass
class Tally:
    """Counted while the soak runs (see `runner`)."""

    outcomes: list[Outcome] = field(default_factory=list)
    false_wakes: int = 0
    turns_outside: int = 0
    unasked: list[str] = field(default_factory=list)
    error_logs: int = 0
    warning_logs: int = 0
    first_errors: list[str] = field(default_factory=list)
    unhandled: list[str] = field(default_factory=list)
    tasks_before: int = 0
    tasks_after: int = 0
    threads_before: int = 0
    threads_after: int = 0
    threads_new: list[str] = field(default_factory=list)
    paced_s: float = 0.0
    free_s: float = 0.0
    sim_s: float = 0.0


@dataclass(frozen=True)
class SoakReport:
    settings: dict[str, Any]
    sim_hours: float
    wall_s: float
    commands: dict[str, Any]
    false_wakes: dict[str, Any]
    unasked_actions: dict[str, Any]
    errors: dict[str, Any]
    memory: dict[str, Any]
    leaks: dict[str, Any]
    stream: dict[str, Any]
    samples: list[Sample]
    load_avg_1_5_15: list[float]

    @property
    def ok(self) -> bool:
        growth = self.memory["rss_growth_pct_per_hour"]
        return (growth is not None and growth < MAX_GROWTH_PCT_PER_HOUR and self.unasked_actions["count"] == 0
                and not self.errors["unhandled"] and self.leaks["tasks_left"] <= 0 and self.leaks["threads_left"] <= 0
                and self.commands["answered"] == self.commands["given"])

    def to_dict(self) -> dict[str, Any]:
        return {"ok": self.ok, "settings": self.settings, "sim_hours": self.sim_hours, "wall_s": self.wall_s,
                "commands": self.commands, "false_wakes": self.false_wakes, "unasked_actions": self.unasked_actions,
                "errors": self.errors, "memory": self.memory, "leaks": self.leaks, "stream": self.stream,
                "load_avg_1_5_15": self.load_avg_1_5_15, "samples": [s.to_dict() for s in self.samples]}

    @classmethod
    def build(cls, settings: dict[str, Any], tally: Tally, samples: list[Sample], wall_s: float, warm_up_s: float,
              *, tv_voice: str) -> SoakReport:
        outcomes = tally.outcomes
        by_kind = {k: {"given": sum(o.command.kind == k for o in outcomes),
                       "answered": sum(o.command.kind == k and o.answered for o in outcomes),
                       "done": sum(o.command.kind == k and o.done for o in outcomes)} for k in KINDS}
        hours = tally.sim_s / 3600.0
        first, last = (samples[0], samples[-1]) if samples else (None, None)
        return cls(
            settings=settings, sim_hours=round(hours, 3), wall_s=round(wall_s, 1),
            commands={"given": len(outcomes), "answered": sum(o.answered for o in outcomes),
                      "done": sum(o.done for o in outcomes), "barge_ins_heard": sum(o.barged_in for o in outcomes),
                      "late": sum(o.late for o in outcomes),
                      "by_kind": by_kind, "not_done": [o.to_dict() for o in outcomes if not o.done],
                      "wall_s_p50": _median([o.wall_s for o in outcomes])},
            false_wakes={"count": tally.false_wakes, "per_hour": round(tally.false_wakes / hours, 2) if hours else None,
                         "turns_outside_commands": tally.turns_outside, "tv_voice": tv_voice},
            unasked_actions={"count": len(tally.unasked), "tools": tally.unasked[:20]},
            errors={"error_logs": tally.error_logs, "warning_logs": tally.warning_logs,
                    "first_errors": tally.first_errors, "unhandled": tally.unhandled},
            memory={"warm_up_s": warm_up_s,
                    "rss_mib_first_last": [first.rss_mib, last.rss_mib] if first and last else None,
                    "rss_growth_pct_per_hour": growth_per_hour(samples, "rss_mib", warm_up_s),
                    "rss_anon_mib_first_last": [first.rss_anon_mib, last.rss_anon_mib] if first and last else None,
                    "rss_anon_growth_pct_per_hour": growth_per_hour(samples, "rss_anon_mib", warm_up_s),
                    "heap_blocks_first_last": [first.heap_blocks, last.heap_blocks] if first and last else None,
                    "heap_growth_pct_per_hour": growth_per_hour(samples, "heap_blocks", warm_up_s),
                    "gc_objects_growth_pct_per_hour": growth_per_hour(samples, "gc_objects", warm_up_s),
                    "fds_first_last": [first.fds, last.fds] if first and last else None},
            leaks={"tasks_before": tally.tasks_before, "tasks_after": tally.tasks_after,
                   "tasks_left": tally.tasks_after - tally.tasks_before, "threads_before": tally.threads_before,
                   "threads_after": tally.threads_after, "threads_new": tally.threads_new,
                   # asyncio's default executor (to_thread) keeps its few workers for reuse: pooled, not leaked
                   "threads_left": sum(not n.startswith("asyncio_") for n in tally.threads_new)},
            stream={"sim_s": round(tally.sim_s, 1), "paced_real_time_s": round(tally.paced_s, 1),
                    "free_running_s": round(tally.free_s, 1),
                    "speed_up": round(tally.sim_s / wall_s, 2) if wall_s else None},
            samples=samples,
            load_avg_1_5_15=[round(x, 2) for x in os.getloadavg()],
        )


def _median(values: list[float]) -> float | None:
    if not values:
        return None
    ordered = sorted(values)
    return round(ordered[len(ordered) // 2], 2)
