"""The manifest format (`mcp.json`, one per middleware node), as pydantic models.

A manifest declares which of a node's RPCs/actions become MCP tools, under which
LLM-facing names, with which parameters (JSON Schema 2020-12) and fixed default
arguments, and which topics become snapshot tools. Anything not declared is never
exposed. See docs/manifest.md for every field.
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

TOOL_NAME_PATTERN = r"^[A-Za-z][A-Za-z0-9_\-]{0,63}$"

EMPTY_OBJECT_SCHEMA: dict[str, Any] = {"type": "object", "properties": {}, "additionalProperties": False}


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)


class ToolAnnotations(_Strict):
    """MCP tool annotations (hints for clients; the server does not enforce them)."""

    title: str | None = None
    readOnlyHint: bool | None = None  # camelCase: MCP's field names
    destructiveHint: bool | None = None
    idempotentHint: bool | None = None
    openWorldHint: bool | None = None


class ToolDecl(_Strict):
    """An RPC or action of the node exposed as an MCP tool."""

    name: str = Field(pattern=TOOL_NAME_PATTERN, description="LLM-facing tool name")
    rpc: str = Field(min_length=1, description="the node's RPC or action this tool calls")
    description: str = Field(min_length=1)
    parameters: dict[str, Any] = Field(
        default_factory=lambda: dict(EMPTY_OBJECT_SCHEMA),
        description="JSON Schema (2020-12) of the arguments object the model passes",
    )
    defaults: dict[str, Any] = Field(
        default_factory=dict,
        description="arguments always passed to the RPC; a key not in `parameters` is fixed "
        "(hidden from the model), a key in `parameters` is a default the model may override",
    )
    annotations: ToolAnnotations = Field(default_factory=ToolAnnotations)
    timeout_s: float | None = Field(
        default=None, gt=0, description="call timeout; default 10 s for RPCs, 300 s for actions"
    )


class SnapshotDecl(_Strict):
    """A topic exposed as a read-only snapshot tool returning the latest message."""

    name: str = Field(pattern=TOOL_NAME_PATTERN)
    topic: str = Field(min_length=1)
    description: str = Field(min_length=1)
    max_age_s: float = Field(gt=0, description="older than this, the snapshot is flagged stale")


class Manifest(_Strict):
    """One node's manifest."""

    schema_: str | None = Field(default=None, alias="$schema")
    node: str = Field(min_length=1, description="the middleware node this manifest describes")
    description: str = ""
    tools: tuple[ToolDecl, ...] = ()
    snapshots: tuple[SnapshotDecl, ...] = ()
