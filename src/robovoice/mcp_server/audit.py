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
"""

from __future__ import annotations

import json
import logging
import os
import threading
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, Literal

from robovoice.errors import ConfigError

log = logging.getLogger(__name__)

_MAX_INLINE_DATA = 256


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
    """Appends `AuditRecord`s to a JSON Lines file; `AuditLog(None)` records nothing."""

    def __init__(self, path: Path | None) -> None:
        self.path = path
        self._lock = threading.Lock()
        self._fd: int | None = None
        if path is not None:
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
                # O_APPEND: every write lands at the end, whatever other writers do.
                self._fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
            except OSError as exc:
                raise ConfigError(f"cannot open the audit log {path}: {exc.strerror or exc} "
                                  "(choose another with --audit-log F)") from None

    @property
    def enabled(self) -> bool:
        return self._fd is not None

    def record(self, record: AuditRecord) -> None:
        if self._fd is None:
            return
        line = json.dumps(record.to_dict(), ensure_ascii=False, default=str) + "\n"
        with self._lock:
            try:
                os.write(self._fd, line.encode("utf-8"))
            except OSError:
                log.exception("cannot append to the audit log %s", self.path)

    def close(self) -> None:
        with self._lock:
            if self._fd is not None:
                os.close(self._fd)
                self._fd = None
