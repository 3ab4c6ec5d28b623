"""One tool call: validate, dispatch to the middleware or the snapshot store, shape the
result, write the audit record.

Two error channels (DESIGN.md §4.6): robot-side failures (`RobotFailure`, including bad
arguments and unknown tools) come back as ``isError`` results with ``{error, message,
hint, details}``; a cancelled call propagates the cancellation (the middleware then
cancels the action on the node). A bug in a node adapter is logged and reported to the
model as ``internal_error`` rather than taking the server down.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Awaitable, Callable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

import mcp_types as types

from robovoice.errors import MiddlewareError, RobotFailure
from robovoice.manifest import CatalogEntry, SnapshotEntry, ToolEntry
from robovoice.mcp_server.audit import AuditLog, AuditRecord
from robovoice.mcp_server.results import failure_result, image_result, value_result
from robovoice.mcp_server.validation import ArgumentValidator
from robovoice.middleware.base import JSON, Feedback, Middleware
from robovoice.snapshot import Snapshot, SnapshotStore, UntrackedTopicError

log = logging.getLogger(__name__)

ProgressFn = Callable[[float, float | None, str | None], Awaitable[None]]
"""``(progress, total, message)``: the SDK's `report_progress` (a no-op without a progressToken)."""


@dataclass(frozen=True, slots=True)
class Caller:
    """Who called, as far as the transport tells: for the audit log."""

    session: str | None = None
    client: str | None = None


ANONYMOUS = Caller()


@dataclass(frozen=True, slots=True)
class _Outcome:
    result: types.CallToolResult
    status: Literal["ok", "error"]
    value: Any = None
    error: dict[str, Any] | None = None


def unknown_tool(name: str, available: list[str]) -> RobotFailure:
    return RobotFailure(
        f"there is no tool {name!r}",
        code="unknown_tool",
        hint="use one of the tools listed in details.available (the list can change when robot parts "
             "go on or off line)",
        details={"tool": name, "available": available},
    )


class ToolCalls:
    """Runs calls against one middleware and one snapshot store, auditing each."""

    def __init__(self, middleware: Middleware, snapshots: SnapshotStore, audit: AuditLog) -> None:
        self._middleware = middleware
        self._snapshots = snapshots
        self._audit = audit

    async def run(
        self,
        name: str,
        arguments: Mapping[str, JSON],
        entry: CatalogEntry | None,
        validator: ArgumentValidator | None,
        *,
        available: Callable[[], list[str]],
        progress: ProgressFn | None = None,
        caller: Caller = ANONYMOUS,
    ) -> types.CallToolResult:
        started, t0 = time.time(), time.perf_counter()
        node = entry.node if entry is not None else None
        rpc = entry.rpc if isinstance(entry, ToolEntry) else None
        try:
            if entry is None or validator is None:
                raise unknown_tool(name, available())
            validator.validate(arguments)
            if isinstance(entry, SnapshotEntry):
                outcome = self._snapshot(entry)
            else:
                outcome = await self._invoke(entry, arguments, progress)
        except RobotFailure as failure:
            outcome = _failure(failure)
        except MiddlewareError as exc:
            outcome = _failure(RobotFailure(str(exc), code="middleware_error",
                                            hint="the robot's middleware is not working; tell the user",
                                            details={"node": node, "rpc": rpc}))
        except asyncio.CancelledError:
            self._record(started, t0, caller, name, node, rpc, arguments, "error",
                         None, {"error": "cancelled", "message": "the client cancelled the call",
                                "hint": None, "details": {}})
            raise
        except Exception as exc:  # a bug below us must not end the session; the model gets a clear error
            log.exception("tool %s failed unexpectedly", name)
            outcome = _failure(RobotFailure(f"{name} failed: {type(exc).__name__}: {exc}", code="internal_error",
                                            hint="this is a fault in the robot software; tell the user",
                                            details={"node": node, "rpc": rpc}))
        self._record(started, t0, caller, name, node, rpc, arguments, outcome.status, outcome.value, outcome.error)
        return outcome.result

    async def _invoke(self, entry: ToolEntry, arguments: Mapping[str, JSON], progress: ProgressFn | None) -> _Outcome:
        call_args = entry.call_arguments(arguments)
        if entry.kind == "action":
            async def on_feedback(feedback: Feedback) -> None:
                if progress is not None:
                    await progress(feedback.progress, feedback.total, feedback.message or None)

            value = await self._middleware.run_action(entry.node, entry.rpc, call_args,
                                                      on_feedback=on_feedback, timeout=entry.timeout_s)
        else:
            value = await self._middleware.call(entry.node, entry.rpc, call_args, timeout=entry.timeout_s)
        return _Outcome(value_result(value), "ok", value)

    def _snapshot(self, entry: SnapshotEntry) -> _Outcome:
        try:
            snapshot = self._snapshots.read(entry.topic, entry.max_age_s)
        except UntrackedTopicError:  # the node has only just joined: tracking is being set up
            snapshot = Snapshot(None, None, None, True, f"no message received yet on {entry.topic!r}", entry.topic)
        image = snapshot.image()
        if image is None:
            body = snapshot.to_dict()
            return _Outcome(value_result(body), "ok", body)
        about = snapshot.to_dict(include_value=False)
        value = snapshot.value if isinstance(snapshot.value, dict) else {}
        about["image"] = {k: v for k, v in value.items() if k != "data"}
        return _Outcome(image_result(image.mime_type, image.data, about), "ok", about)

    def _record(self, started: float, t0: float, caller: Caller, tool: str, node: str | None, rpc: str | None,
                arguments: Mapping[str, JSON], status: Literal["ok", "error"], value: Any,
                error: dict[str, Any] | None) -> None:
        self._audit.record(AuditRecord(
            started=started, session=caller.session, client=caller.client, tool=tool, node=node, rpc=rpc,
            arguments=dict(arguments), outcome=status, result=value, error=error,
            duration_ms=(time.perf_counter() - t0) * 1000.0,
        ))


def _failure(failure: RobotFailure) -> _Outcome:
    return _Outcome(failure_result(failure), "error", error=failure.to_dict())
