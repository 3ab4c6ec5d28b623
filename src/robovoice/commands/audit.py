"""`robovoice audit [FILE] [--tool T] [--errors] [--since WHEN] [--summary] [--json]`.

Reads the MCP server's audit log (default: ``audit.jsonl`` in the state dir) and its rotated
files, oldest first; a torn last line (a writer killed mid-record) is skipped with a note on
stderr. Without ``--summary``: one line per call (``--json``: the records as JSON Lines).
With ``--summary``: calls, errors and durations per tool, error codes, and the time span.
"""

from __future__ import annotations

import argparse
import json
import re
import statistics
import sys
from collections import Counter, defaultdict
from datetime import UTC, datetime, timedelta
from pathlib import Path
from typing import Any

from robovoice.errors import ConfigError

_RELATIVE = re.compile(r"^(\d+(?:\.\d+)?)\s*(s|m|h|d)$")
_UNITS = {"s": 1.0, "m": 60.0, "h": 3600.0, "d": 86400.0}


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    audit = subparsers.add_parser("audit", help="read, filter and summarise the MCP server's audit log")
    audit.add_argument("file", nargs="?", type=Path, help="the log (default: audit.jsonl in the state dir)")
    audit.add_argument("--tool", action="append", metavar="T", help="only calls of this tool (repeatable)")
    audit.add_argument("--errors", action="store_true", help="only calls that failed")
    audit.add_argument("--since", type=since_time, metavar="WHEN",
                       help="only calls from then on: an ISO time (2026-11-23T09:00, UTC unless it says) "
                            "or an age such as 90s, 15m, 2h, 1d")
    audit.add_argument("--no-rotated", action="store_true", help="read FILE only, not FILE.1, FILE.2, …")
    audit.add_argument("--summary", action="store_true", help="counts and durations per tool instead of the calls")
    audit.add_argument("--json", action="store_true", help="machine-readable output")
    audit.set_defaults(run=run)


def since_time(text: str, now: datetime | None = None) -> datetime:
    """``--since`` value → an aware UTC time."""
    match = _RELATIVE.match(text.strip())
    if match:
        return (now or datetime.now(UTC)) - timedelta(seconds=float(match[1]) * _UNITS[match[2]])
    try:
        when = datetime.fromisoformat(text.strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an ISO time or an age such as 15m, 2h, 1d, not {text!r}") from None
    return when if when.tzinfo is not None else when.replace(tzinfo=UTC)


def _time(record: dict[str, Any]) -> datetime | None:
    try:
        when = datetime.fromisoformat(str(record.get("time")))
    except ValueError:
        return None
    return when if when.tzinfo is not None else when.replace(tzinfo=UTC)


def select(records: list[dict[str, Any]], *, tools: list[str] | None = None, errors: bool = False,
           since: datetime | None = None) -> list[dict[str, Any]]:
    """The records that pass the filters, in file order."""
    chosen = []
    for record in records:
        if tools and record.get("tool") not in tools:
            continue
        if errors and record.get("outcome") != "error":
            continue
        if since is not None:
            when = _time(record)
            if when is None or when < since:
                continue
        chosen.append(record)
    return chosen


def summarise(records: list[dict[str, Any]]) -> dict[str, Any]:
    """Counts, errors and durations (ms, median and p95) per tool; error codes; the time span."""
    durations: dict[str, list[float]] = defaultdict(list)
    calls: Counter[str] = Counter()
    failed: Counter[str] = Counter()
    codes: Counter[str] = Counter()
    for record in records:
        tool = str(record.get("tool"))
        calls[tool] += 1
        duration = record.get("duration_ms")
        if isinstance(duration, int | float):
            durations[tool].append(float(duration))
        if record.get("outcome") == "error":
            failed[tool] += 1
            error = record.get("error")
            codes[str(error.get("error")) if isinstance(error, dict) else "?"] += 1
    times = [t for t in (_time(r) for r in records) if t is not None]
    return {
        "calls": len(records),
        "errors": sum(failed.values()),
        "first": min(times).isoformat() if times else None,
        "last": max(times).isoformat() if times else None,
        "tools": {tool: {"calls": calls[tool], "errors": failed[tool],
                         "median_ms": _quantile(durations[tool], 0.5), "p95_ms": _quantile(durations[tool], 0.95)}
                  for tool in sorted(calls)},
        "error_codes": dict(codes.most_common()),
    }


def _quantile(values: list[float], q: float) -> float | None:
    if not values:
        return None
    if len(values) == 1:
        return round(values[0], 3)
    return round(statistics.quantiles(values, n=100, method="inclusive")[round(q * 100) - 1], 3)


def _line(record: dict[str, Any]) -> str:
    outcome = record.get("outcome")
    if outcome == "error":
        error = record.get("error")
        what = f"ERROR {error.get('error')}: {error.get('message')}" if isinstance(error, dict) else "ERROR"
    else:
        what = "ok " + json.dumps(record.get("result"), ensure_ascii=False, default=str)
    args = json.dumps(record.get("arguments"), ensure_ascii=False, default=str)
    duration = record.get("duration_ms")
    ms = f"{duration:.1f} ms" if isinstance(duration, int | float) else "? ms"
    text = f"{record.get('time')}  {record.get('tool')} {args}  {ms}  {what}"
    return text if len(text) <= 240 else text[:237] + "..."


def _print_summary(summary: dict[str, Any]) -> None:
    print(f"{summary['calls']} calls, {summary['errors']} errors, from {summary['first']} to {summary['last']}")
    if summary["tools"]:
        width = max(len(t) for t in summary["tools"])
        print(f"{'tool':<{width}}  {'calls':>6}  {'errors':>6}  {'median ms':>9}  {'p95 ms':>9}")
        for tool, row in summary["tools"].items():
            med = "-" if row["median_ms"] is None else f"{row['median_ms']:.1f}"
            p95 = "-" if row["p95_ms"] is None else f"{row['p95_ms']:.1f}"
            print(f"{tool:<{width}}  {row['calls']:>6}  {row['errors']:>6}  {med:>9}  {p95:>9}")
    for code, count in summary["error_codes"].items():
        print(f"error {code}: {count}")


def run(args: argparse.Namespace) -> int:
    from robovoice.mcp_server.audit import default_audit_path, read_audit

    path: Path = args.file or default_audit_path()
    if not path.exists():
        raise ConfigError(f"no audit log at {path} (the MCP server writes one when it serves tools; "
                          "name another file as the first argument)")
    reading = read_audit(path, rotated=not args.no_rotated)
    for skipped in reading.skipped:
        kind = "an incomplete last line (a writer stopped mid-record)" if skipped.torn else "a damaged line"
        print(f"robovoice audit: skipped {kind}: {skipped.path}:{skipped.line}", file=sys.stderr)
    records = select(reading.records, tools=args.tool, errors=args.errors, since=args.since)
    if args.summary:
        summary = summarise(records)
        summary["skipped_lines"] = len(reading.skipped)
        if args.json:
            print(json.dumps(summary, indent=1))
        else:
            _print_summary(summary)
        return 0
    for record in records:
        print(json.dumps(record, ensure_ascii=False) if args.json else _line(record))
    return 0
