"""The console's work, apart from HTTP: typed turns, tools by hand, the audit log, the state.

One `Console` per served page. Typed turns go through the same `Assistant` the command line
uses (the voice pipeline's own one when the microphone is on, so typed and spoken requests
are one conversation); their events reach the page through the `EventHub` as they happen.
The audit log is the console's own record of every tool call made through it (the
assistant's, the voice pipeline's and those by hand), newest first; the robot's state
polling is not recorded there.
"""

from __future__ import annotations

import asyncio
import json
import time
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass
from datetime import UTC, datetime
from typing import Any

import mcp_types as types

from robovoice.assistant.events import SentenceReady, ToolCalled, ToolReturned, TurnEvent
from robovoice.assistant.loop import Assistant
from robovoice.assistant.robot_tools import RobotTools
from robovoice.console.hub import EventHub
from robovoice.console.jsonable import jsonable
from robovoice.console.voice import VoiceBridge
from robovoice.console.watch import RobotWatcher
from robovoice.llm.base import LLMBackend

MAX_AUDIT = 1000
HAND_CALL_TIMEOUT_S = 330.0


@dataclass(frozen=True, slots=True)
class AuditEntry:
    time: float
    source: str  # typed, voice, hand
    tool: str
    arguments: dict[str, Any]
    is_error: bool
    error: str | None
    result: Any
    duration_ms: float

    def to_json(self) -> dict[str, Any]:
        return {"time": datetime.fromtimestamp(self.time, UTC).isoformat(timespec="milliseconds"),
                "source": self.source, "tool": self.tool, "arguments": jsonable(self.arguments),
                "outcome": "error" if self.is_error else "ok", "error": self.error,
                "result": _shrink(jsonable(self.result)), "duration_ms": round(self.duration_ms, 1)}


def _shrink(value: Any) -> Any:
    """Long base64 payloads (pictures) replaced by their size, as in the server's audit log."""
    if isinstance(value, dict):
        return {k: f"<{len(v)} bytes base64>" if k == "data" and isinstance(v, str) and len(v) > 256 else _shrink(v)
                for k, v in value.items()}
    if isinstance(value, list):
        return [_shrink(v) for v in value]
    return value


class ConsoleAudit:
    """Tool calls made through the console, newest first (bounded)."""

    def __init__(self, hub: EventHub, limit: int = MAX_AUDIT) -> None:
        self._entries: deque[AuditEntry] = deque(maxlen=limit)
        self._pending: dict[str, tuple[float, str, dict[str, Any]]] = {}
        self._hub = hub

    def add(self, entry: AuditEntry) -> None:
        self._entries.append(entry)
        self._hub.broadcast({"type": "audit", "record": entry.to_json()})

    def observe(self, event: object, source: str) -> None:
        """Pair an assistant's `ToolCalled` with its `ToolReturned` into one entry."""
        match event:
            case ToolCalled(call_id=call_id, name=name, arguments=arguments):
                self._pending[call_id] = (time.time(), name, dict(arguments))
            case ToolReturned(call_id=call_id, name=name, is_error=is_error, error=error, result=result,
                              duration_ms=duration, text=text):
                started, _, arguments = self._pending.pop(call_id, (time.time(), name, {}))
                self.add(AuditEntry(started, source, name, arguments, is_error, error,
                                    result if result is not None else text, duration))
            case _:
                pass

    def query(self, *, tool: str | None = None, errors: bool | None = None, limit: int = 100) -> list[dict[str, Any]]:
        out: list[dict[str, Any]] = []
        for entry in reversed(self._entries):
            if tool is not None and entry.tool != tool:
                continue
            if errors is not None and entry.is_error != errors:
                continue
            out.append(entry.to_json())
            if len(out) >= limit:
                break
        return out


class Console:
    """See the module docstring. `run()` polls the robot (and runs the voice) until cancelled."""

    def __init__(self, tools: RobotTools, backend: LLMBackend, *, voice: VoiceBridge | None = None,
                 robot_name: str = "robot") -> None:
        self.tools = tools
        self.backend = backend
        self.voice = voice
        self.robot_name = robot_name
        self.hub = EventHub()
        self.audit = ConsoleAudit(self.hub)
        self.watcher = RobotWatcher(tools.client, on_state=self._on_state, watching=lambda: self.hub.listeners > 0)
        self._assistant = Assistant(backend, tools)
        self._typed = asyncio.Lock()
        if voice is not None:
            voice.attach(self.hub, self.audit)

    @property
    def assistant(self) -> Assistant:
        """The conversation: the voice pipeline's when it runs, else the console's own."""
        pipeline = self.voice.pipeline if self.voice is not None else None
        return pipeline.assistant if pipeline is not None else self._assistant

    def observe(self, event: object, source: str = "voice") -> None:
        """Show a voice pipeline event that another command's pipeline produced (`beside`)."""
        self.hub.voice_event(event)
        self.audit.observe(event, source)

    def _on_state(self, state: dict[str, Any]) -> None:
        self.hub.broadcast({"type": "state", "state": state})

    async def run(self) -> None:
        async with asyncio.TaskGroup() as group:
            group.create_task(self.watcher.run(), name="console-watch")
            if self.voice is not None:
                group.create_task(self.voice.run(), name="console-voice")

    def state(self, turns: int = 20) -> dict[str, Any]:
        return {"robot": self.watcher.state(), "turns": self.hub.recent_turns(turns),
                "voice": self.voice.status() if self.voice is not None else {"state": "off"},
                "model": self.backend.name, "robot_name": self.robot_name}

    # --- typed turns -------------------------------------------------------------------

    async def say(self, text: str) -> dict[str, Any]:
        """One typed turn through the assistant; the turn as JSON (its events in order)."""
        async with self._typed:
            record = self.hub.open_turn("typed")
            speech = self.voice.pipeline.speech if self.voice is not None and self.voice.pipeline else None

            def observe(event: TurnEvent) -> None:
                self.hub.add(record, event)
                self.audit.observe(event, "typed")
                if speech is not None and isinstance(event, SentenceReady):
                    speech.say(event.text, kind="reply")  # the robot's voice plays in the page

            try:
                result = await self.assistant.turn(text, observer=observe)
                answer = await self.voice.typed_answer(record.id) if speech is not None and self.voice else None
            except BaseException:
                self.hub.close_turn(record)
                raise
            self.hub.close_turn(record, result.metrics.as_dict(), answer)
            return {"turn": record.id, "text": text, "reply": result.reply, "fell_back": result.fell_back,
                    "calls": [{"name": c.name, "arguments": jsonable(c.arguments)} for c in result.calls],
                    "events": list(record.events), "latency_ms": record.latency_ms, "answer": answer}

    # --- tools by hand -----------------------------------------------------------------

    async def tool_list(self) -> list[dict[str, Any]]:
        """Every tool the robot offers (those for the model and those for people), as MCP lists them."""
        model_tools = {spec.name for spec in await self.tools.specs()}
        listing = await self.tools.client.list_tools()
        out = []
        for tool in listing.tools:
            annotations = tool.annotations.model_dump(by_alias=True, exclude_none=True) if tool.annotations else {}
            out.append({"name": tool.name, "description": tool.description or "", "input_schema": tool.input_schema,
                        "annotations": annotations, "meta": jsonable(tool.meta or {}),
                        "for_model": tool.name in model_tools})
        return out

    async def call(self, name: str, arguments: Mapping[str, Any]) -> dict[str, Any]:
        """Call one tool by hand, exactly as the model would; its result as JSON."""
        started, wall = time.perf_counter(), time.time()
        try:
            result = await self.tools.client.call_tool(name, dict(arguments), read_timeout_seconds=HAND_CALL_TIMEOUT_S)
        except Exception as exc:  # transport failure: reported like a tool error
            duration = (time.perf_counter() - started) * 1000.0
            body = {"error": "tool_unavailable", "message": str(exc) or type(exc).__name__}
            self.audit.add(AuditEntry(wall, "hand", name, dict(arguments), True, "tool_unavailable", body, duration))
            return {"tool": name, "is_error": True, "error": "tool_unavailable", "structured": body, "content": [],
                    "duration_ms": round(duration, 1)}
        duration = (time.perf_counter() - started) * 1000.0
        content = [_block(b) for b in result.content]
        structured = result.structured_content
        if structured is None:
            structured = _json_text(content)
        error = None
        if result.is_error:
            code = structured.get("error") if isinstance(structured, dict) else None
            error = code if isinstance(code, str) and code else "tool_error"
        self.audit.add(AuditEntry(wall, "hand", name, dict(arguments), bool(result.is_error), error,
                                  structured, duration))
        return {"tool": name, "is_error": bool(result.is_error), "error": error, "structured": jsonable(structured),
                "content": content, "duration_ms": round(duration, 1)}


def _block(block: Any) -> dict[str, Any]:
    if isinstance(block, types.TextContent):
        return {"type": "text", "text": block.text}
    if isinstance(block, types.ImageContent):
        return {"type": "image", "mime": block.mime_type, "data": block.data}
    return {"type": getattr(block, "type", "other")}


def _json_text(content: list[dict[str, Any]]) -> Any:
    for block in content:
        if block["type"] == "text":
            try:
                return json.loads(block["text"])
            except ValueError:
                return None
    return None
