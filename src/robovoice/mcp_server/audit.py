"""The append-only audit log of tool calls (DESIGN.md §8).

One JSON object per line, one line per tool call, written with a single ``write`` on a
file opened in append mode, so concurrent writers (several server processes) never
interleave inside a line. Fields:

``time``         ISO 8601 UTC time the call started
``session``      the MCP session id (streamable HTTP), or null (stdio, in-process)
``client``       ``name/version`` the client announced, or null
``tool``         the tool name the client asked for
``node``, ``rpc`` where the call went (null for unknown tools; ``rpc`` is null for snapshots)
``arguments``    the arguments as the client sent them
``outcome``      ``"ok"`` or ``"error"``
``result``       the result value (ok), or ``error`` = ``{error, message, hint, details}``
``duration_ms``  wall time of the call in milliseconds

Images are not copied into the log: a ``data`` string longer than 256 characters is
replaced by ``"<N bytes base64>"``.

Crash safety: each record is encoded whole, then written with one ``os.write`` on an
``O_APPEND`` descriptor (no user-space buffer), so a ``kill -9`` at any moment leaves at
most the line being written incomplete; `read_audit` skips such a torn line and says so.
Rotation by size: when a line would take the file past `max_bytes`, ``audit.jsonl`` becomes
``audit.jsonl.1`` (``.1`` → ``.2`` …, `keep` files kept), under an ``flock`` so several
writing processes rotate once. A full or read-only disk never fails a tool call: the failure
is logged once (then once more when writing works again) and counted in `failures`.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import logging
import os
import threading
from collections.abc import Iterator
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, Literal

from robovoice.errors import ConfigError

log = logging.getLogger(__name__)

_MAX_INLINE_DATA = 256
DEFAULT_MAX_BYTES = 16 * 1024 * 1024
DEFAULT_KEEP = 5


def default_audit_path() -> Path:
    """Where the audit log goes when nothing else is configured: ``audit.jsonl`` in the user's
    state dir (``$ROBOVOICE_STATE_DIR``, else ``$XDG_STATE_HOME/robovoice``, else
    ``~/.local/state/robovoice``; see `robovoice.config.environment`)."""
    from robovoice.config import environment

    return environment().state_dir / "audit.jsonl"


@dataclass(frozen=True, slots=True)
class AuditRecord:
    """One tool call, as written to the log."""

    started: float
    session: str | None
    client: str | None
    tool: str
    node: str | None
    rpc: str | None
    arguments: dict[str, Any]
    outcome: Literal["ok", "error"]
    result: Any
    error: dict[str, Any] | None
    duration_ms: float

    def to_dict(self) -> dict[str, Any]:
        body: dict[str, Any] = {
            "time": datetime.fromtimestamp(self.started, UTC).isoformat(timespec="milliseconds"),
            "session": self.session,
            "client": self.client,
            "tool": self.tool,
            "node": self.node,
            "rpc": self.rpc,
            "arguments": _shrink(self.arguments),
            "outcome": self.outcome,
            "duration_ms": round(self.duration_ms, 3),
        }
        if self.outcome == "ok":
            body["result"] = _shrink(self.result)
        else:
            body["error"] = self.error
        return body


def _shrink(value: Any) -> Any:
    """Replace long base64 payloads (camera images) by their size."""
    if isinstance(value, dict):
        return {
            k: (f"<{len(v)} bytes base64>" if k == "data" and isinstance(v, str) and len(v) > _MAX_INLINE_DATA
                else _shrink(v))
            for k, v in value.items()
        }
    if isinstance(value, list):
        return [_shrink(v) for v in value]
    return value


class AuditLog:
    """Appends `AuditRecord`s to a JSON Lines file; `AuditLog(None)` records nothing.

    `max_bytes`: rotate when a line would take the file past this size (0: never rotate);
    `keep`: rotated files kept (``.1`` newest … ``.keep`` oldest). Writing never raises.
    """

    def __init__(self, path: Path | None, *, max_bytes: int = DEFAULT_MAX_BYTES, keep: int = DEFAULT_KEEP) -> None:
        if max_bytes < 0 or keep < 1:
            raise ConfigError(f"audit log rotation needs max_bytes >= 0 and keep >= 1, not {max_bytes}, {keep}")
        self.path = path
        self.max_bytes = max_bytes
        self.keep = keep
        self.written = 0
        self.failures = 0
        self._failing = False
        self._lock = threading.Lock()
        self._fd: int | None = None
        if path is not None:
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
                self._fd = self._open(path)
                self._end_torn_line(path)
            except OSError as exc:
                raise ConfigError(f"cannot open the audit log {path}: {exc.strerror or exc} "
                                  "(choose another with --audit-log F)") from None

    @staticmethod
    def _open(path: Path) -> int:
        # O_APPEND: every write lands at the end, whatever other writers do. Readable too, so
        # the torn-line check reads the file this descriptor has, not whatever `path` is now.
        return os.open(path, os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_CLOEXEC, 0o600)

    def _end_torn_line(self, path: Path) -> None:
        """A writer killed mid-line left the file without a final newline: end that line, so
        our first record does not merge into it."""
        assert self._fd is not None
        size = os.fstat(self._fd).st_size
        if size == 0:
            return
        # Through our descriptor: a peer may have rotated `path` since we opened it, and a new,
        # shorter file there read as torn put an empty line into the rotated one (CI, stop 51).
        if os.pread(self._fd, 1, size - 1) != b"\n":
            os.write(self._fd, b"\n")
            log.warning("the audit log %s ended with an incomplete line (a writer was killed mid-record); "
                        "readers skip it", path)

    @property
    def enabled(self) -> bool:
        return self._fd is not None

    def record(self, record: AuditRecord) -> None:
        """Append one line. Never raises: a failure is counted and logged (once per outage)."""
        if self._fd is None:
            return
        try:
            line = (json.dumps(record.to_dict(), ensure_ascii=False, default=str) + "\n").encode("utf-8")
        except (TypeError, ValueError, RecursionError) as exc:
            self._failed(f"cannot encode the record of {record.tool}: {exc}")
            return
        with self._lock:
            if self._fd is None:  # closed meanwhile
                return
            try:
                self._rotate_if_needed(len(line))
                self._write(line)
            except OSError as exc:
                self._failed(f"cannot append to the audit log {self.path}: {exc.strerror or exc}")
                return
        self.written += 1
        if self._failing:
            self._failing = False
            log.warning("the audit log %s is being written again (%d records lost meanwhile)", self.path,
                        self.failures)

    def _write(self, line: bytes) -> None:
        assert self._fd is not None
        before = os.fstat(self._fd).st_size
        done = os.write(self._fd, line)
        if done < len(line):  # disk full or file size limit mid-line: take the torn part back
            with contextlib.suppress(OSError):
                if os.fstat(self._fd).st_size == before + done:
                    os.ftruncate(self._fd, before)
            raise OSError(28, "short write (disk full or file size limit)")

    def _rotate_if_needed(self, size: int) -> None:
        assert self._fd is not None and self.path is not None
        if self.max_bytes == 0:
            return
        current = os.fstat(self._fd)
        if current.st_size == 0 or current.st_size + size <= self.max_bytes:
            return
        fcntl.flock(self._fd, fcntl.LOCK_EX)
        try:
            try:
                on_disk = os.stat(self.path)
                rotated_elsewhere = (on_disk.st_ino, on_disk.st_dev) != (current.st_ino, current.st_dev)
            except FileNotFoundError:
                rotated_elsewhere = True
            if not rotated_elsewhere:
                for n in range(self.keep - 1, 0, -1):
                    older = rotated_path(self.path, n)
                    if older.exists():
                        os.replace(older, rotated_path(self.path, n + 1))
                os.replace(self.path, rotated_path(self.path, 1))
            fresh = self._open(self.path)
        finally:
            fcntl.flock(self._fd, fcntl.LOCK_UN)
        os.close(self._fd)
        self._fd = fresh

    def _failed(self, message: str) -> None:
        self.failures += 1
        if not self._failing:
            self._failing = True
            log.error("%s; tool calls go on unaudited until it can be written again", message)

    def close(self) -> None:
        with self._lock:
            if self._fd is not None:
                os.close(self._fd)
                self._fd = None


def rotated_path(path: Path, n: int) -> Path:
    """``audit.jsonl`` → ``audit.jsonl.<n>``."""
    return path.with_name(f"{path.name}.{n}")


@dataclass(frozen=True, slots=True)
class SkippedLine:
    """A line `read_audit` could not parse: `torn` when it is a file's unterminated last line
    (a writer killed mid-line), else damaged."""

    path: Path
    line: int
    torn: bool


@dataclass(slots=True)
class AuditReading:
    records: list[dict[str, Any]] = field(default_factory=list)
    skipped: list[SkippedLine] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)


def audit_files(path: Path, *, rotated: bool = True) -> list[Path]:
    """`path` and, with `rotated`, its rotated files that exist, oldest first. Every number
    counts, not only an unbroken run from 1: a writer killed in the middle of a rotation's
    renames leaves a gap in the numbers, and the files past it still hold records."""
    older: list[tuple[int, Path]] = []
    if rotated:
        prefix = f"{path.name}."
        for candidate in path.parent.glob(f"{path.name}.*"):
            number = candidate.name[len(prefix):]
            if number.isdigit() and candidate.is_file():
                older.append((int(number), candidate))
    return [*(p for _, p in sorted(older, reverse=True)), *([path] if path.exists() else [])]


def iter_lines(path: Path) -> Iterator[tuple[int, dict[str, Any] | None, bool]]:
    """``(line number, record or None if unparsable, whether the line was terminated)``."""
    with path.open("rb") as f:
        for number, raw in enumerate(f, start=1):
            terminated = raw.endswith(b"\n")
            try:
                value = json.loads(raw)
            except ValueError:  # also UnicodeDecodeError
                value = None
            yield number, value if isinstance(value, dict) else None, terminated


def read_audit(path: Path, *, rotated: bool = True) -> AuditReading:
    """Every record in `path` (and its rotated files, oldest first), skipping torn or damaged lines."""
    reading = AuditReading()
    for file in audit_files(path, rotated=rotated):
        reading.files.append(file)
        for number, value, terminated in iter_lines(file):
            if value is None:
                reading.skipped.append(SkippedLine(file, number, torn=not terminated))
            else:
                reading.records.append(value)
    return reading
