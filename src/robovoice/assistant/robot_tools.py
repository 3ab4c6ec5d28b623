"""The assistant's side of MCP: the robot's tools as the model sees them.

Wraps a connected official SDK `mcp.Client`: lists the tools and turns them into
`ToolSpec`s, calls them (with progress), and refreshes the list when the server sends
`notifications/tools/list_changed`. Each tool's manifest ``voice`` section (its role for the
voice pipeline and its phrases, docs/manifest.md) comes in the tool's ``_meta``; `voice()`
gives them by tool name.
"""

from __future__ import annotations

import json
import logging
import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Protocol

import mcp_types as types
from mcp import Client
from mcp.shared.dispatcher import ProgressFnT
from pydantic import ValidationError

from robovoice.llm.base import ToolSpec
from robovoice.manifest.model import FOR_MODEL_META_KEY
from robovoice.manifest.voice import META_KEY, VoiceDecl

log = logging.getLogger(__name__)

ProgressCallback = ProgressFnT  # async (progress, total, message) -> None


@dataclass(frozen=True, slots=True)
class ToolOutcome:
    """What a tool call gave back, flattened for the model: JSON text, error flag, duration."""

    text: str
    is_error: bool
    duration_ms: float
    structured: Any = None

    @property
    def error(self) -> str | None:
        """The structured error code of a failed call (``tool_error`` when the server sent none)."""
        if not self.is_error:
            return None
        code = self.structured.get("error") if isinstance(self.structured, dict) else None
        return code if isinstance(code, str) and code else "tool_error"


def _content_text(result: types.CallToolResult) -> str:
    parts: list[str] = []
    for block in result.content:
        if isinstance(block, types.TextContent):
            parts.append(block.text)
        elif isinstance(block, types.ImageContent):
            size = len(block.data) * 3 // 4
            parts.append(f"[an image was captured: {block.mime_type}, about {size // 1024} kB]")
    return "\n".join(parts) if parts else json.dumps(result.structured_content or {})


class Toolbox(Protocol):
    """The robot's tools as the assistant and the voice pipeline use them: `RobotTools` over
    MCP, or a test's stand-in. `specs` returns the same list object until the tools change."""

    async def specs(self) -> list[ToolSpec]: ...

    async def call(
        self, name: str, arguments: dict[str, Any], on_progress: ProgressCallback | None = None
    ) -> ToolOutcome: ...

    def voice(self) -> Mapping[str, VoiceDecl]:
        """The tools' voice sections by tool name, as of the last `specs()`."""
        ...


def voice_section(name: str, meta: Mapping[str, Any] | None) -> VoiceDecl | None:
    """The voice section in a tool's ``_meta`` (None when absent or malformed, with a warning)."""
    raw = (meta or {}).get(META_KEY)
    if raw is None:
        return None
    try:
        return VoiceDecl.model_validate(raw)
    except ValidationError as exc:
        log.warning("tool %s: its %s metadata is not understood (%s); the voice pipeline ignores it",
                    name, META_KEY, exc.errors()[0]["msg"] if exc.errors() else exc)
        return None


class RobotTools:
    """The robot's MCP tools for one assistant. `handle_message` must be the client's
    `message_handler` so list changes are noticed."""

    def __init__(self, call_timeout_s: float = 330.0) -> None:
        self._client: Client | None = None
        self._specs: list[ToolSpec] = []
        self._voice: dict[str, VoiceDecl] = {}
        self._stale = True
        self._call_timeout_s = call_timeout_s

    def attach(self, client: Client) -> None:
        self._client = client
        self._stale = True

    async def handle_message(self, message: object) -> None:
        if isinstance(message, types.ToolListChangedNotification):
            log.info("robot tool list changed")
            self._stale = True
        elif isinstance(message, Exception):
            log.warning("MCP transport problem: %s", message)

    @property
    def client(self) -> Client:
        if self._client is None:
            raise RuntimeError("RobotTools used before attach()")
        return self._client

    async def specs(self) -> list[ToolSpec]:
        """The current tool list (fetched again after a list change)."""
        if self._stale:
            listing = await self.client.list_tools(cache_mode="refresh")
            self._specs = [  # tools marked for people and programs only (a map) are not the model's
                ToolSpec(tool.name, tool.description or tool.name, tool.input_schema,
                         read_only=bool(tool.annotations and tool.annotations.read_only_hint))
                for tool in listing.tools if (tool.meta or {}).get(FOR_MODEL_META_KEY) is not False
            ]
            sections = {tool.name: voice_section(tool.name, tool.meta) for tool in listing.tools}
            self._voice = {name: section for name, section in sections.items() if section is not None}
            self._stale = False
            log.info("robot offers %d tools", len(self._specs))
        return self._specs

    def voice(self) -> Mapping[str, VoiceDecl]:
        """The tools' voice sections by name, as of the last `specs()`."""
        return dict(self._voice)

    async def call(
        self, name: str, arguments: dict[str, Any], on_progress: ProgressCallback | None = None
    ) -> ToolOutcome:
        start = time.perf_counter()
        try:
            result = await self.client.call_tool(
                name, arguments, read_timeout_seconds=self._call_timeout_s, progress_callback=on_progress
            )
        except Exception as exc:  # transport or protocol failure: tell the model, keep the turn alive
            log.warning("tool %s failed at the MCP level: %s", name, exc)
            body = {"error": "tool_unavailable", "message": str(exc) or type(exc).__name__,
                    "hint": "the robot could not be reached; tell the user", "details": {"tool": name}}
            return ToolOutcome(json.dumps(body), True, (time.perf_counter() - start) * 1000.0, body)
        return ToolOutcome(
            _content_text(result), bool(result.is_error), (time.perf_counter() - start) * 1000.0,
            result.structured_content,
        )
