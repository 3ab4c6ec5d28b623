"""The manifest format (`mcp.json`, one per middleware node), as pydantic models.

A manifest declares which of a node's RPCs/actions become MCP tools, under which
LLM-facing names, with which parameters (JSON Schema 2020-12) and fixed default
arguments, and which topics become snapshot tools. Anything not declared is never
exposed. See docs/manifest.md for every field.
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field, field_validator

from robovoice.manifest.ros2_model import Ros2SnapshotBinding, Ros2ToolBinding
from robovoice.manifest.voice import VoiceDecl

TOOL_NAME_PATTERN = r"^[A-Za-z][A-Za-z0-9_\-]{0,63}$"

EMPTY_OBJECT_SCHEMA: dict[str, Any] = {"type": "object", "properties": {}, "additionalProperties": False}

# A tool with ``"for_model": false`` is for people and programs (a console's map), not the model:
# MCP lists it with ``_meta[FOR_MODEL_META_KEY] = false`` and the assistant leaves it out.
FOR_MODEL_META_KEY = "robovoice/for_model"
FOR_MODEL_DESCRIPTION = ("offered to the language model (default true); false: for people and programs only, "
                         "e.g. the map a console draws; still an MCP tool, marked in its _meta")


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)


class ToolAnnotations(_Strict):
    """MCP tool annotations (hints for clients; the server does not enforce them)."""

    title: str | None = Field(default=None, description="human-readable title of the tool")
    # camelCase: MCP's own field names
    readOnlyHint: bool | None = Field(default=None, description="the tool does not change anything")
    destructiveHint: bool | None = Field(
        default=None, description="the tool may undo or destroy something (meaningful when not read-only)"
    )
    idempotentHint: bool | None = Field(
        default=None, description="calling it again with the same arguments has no further effect"
    )
    openWorldHint: bool | None = Field(
        default=None, description="the tool acts on the world outside (for a robot: it moves or talks)"
    )


class ToolDecl(_Strict):
    """An RPC or action of the node exposed as an MCP tool."""

    name: str = Field(pattern=TOOL_NAME_PATTERN, description="LLM-facing tool name")
    rpc: str = Field(min_length=1, description="the node's RPC or action this tool calls")
    description: str = Field(min_length=1, description="what the tool does, for the model")
    parameters: dict[str, Any] = Field(
        default_factory=lambda: dict(EMPTY_OBJECT_SCHEMA),
        description="JSON Schema (2020-12) of the arguments object the model passes",
        json_schema_extra={"required": ["type"], "properties": {"type": {"const": "object"}}},
    )
    defaults: dict[str, Any] = Field(
        default_factory=dict,
        description="arguments always passed to the RPC; a key not in `parameters` is fixed "
        "(hidden from the model), a key in `parameters` is a default the model may override",
    )
    annotations: ToolAnnotations = Field(
        default_factory=ToolAnnotations, description="MCP tool annotations (hints for clients)"
    )
    timeout_s: float | None = Field(
        default=None, gt=0, description="call timeout; default 10 s for RPCs, 300 s for actions"
    )
    voice: VoiceDecl | None = Field(
        default=None, description="its role for the voice pipeline (stop, motion) and what the robot says "
        "when it starts, makes progress, succeeds or fails (docs/manifest.md)"
    )
    for_model: bool = Field(default=True, description=FOR_MODEL_DESCRIPTION)

    @field_validator("voice")
    @classmethod
    def _tool_role(cls, voice: VoiceDecl | None) -> VoiceDecl | None:
        if voice is not None and voice.role == "pose":
            raise ValueError("the pose role belongs to a snapshot (its value says whether the robot moves)")
        return voice

    ros2: Ros2ToolBinding | None = Field(
        default=None, description="ros2:// only: the ROS 2 service or action (named by `rpc`) and its type; "
        "the parameters are derived from the type (docs/ros2.md)"
    )


class SnapshotDecl(_Strict):
    """A topic exposed as a read-only snapshot tool returning the latest message."""

    name: str = Field(pattern=TOOL_NAME_PATTERN, description="LLM-facing tool name")
    topic: str = Field(min_length=1, description="the topic the node publishes")
    description: str = Field(min_length=1, description="what the snapshot tells, for the model")
    max_age_s: float = Field(gt=0, description="older than this, the snapshot is flagged stale")
    voice: VoiceDecl | None = Field(
        default=None, description="its role for the voice pipeline: pose (the value says whether the robot moves)"
    )
    for_model: bool = Field(default=True, description=FOR_MODEL_DESCRIPTION)

    @field_validator("voice")
    @classmethod
    def _snapshot_role(cls, voice: VoiceDecl | None) -> VoiceDecl | None:
        if voice is not None and voice.role not in (None, "pose"):
            raise ValueError(f"a snapshot's voice role can only be pose, not {voice.role}")
        return voice

    ros2: Ros2SnapshotBinding | None = Field(
        default=None, description="ros2:// only: the ROS 2 message type of the topic (docs/ros2.md)"
    )


class Manifest(_Strict):
    """One node's manifest."""

    schema_: str | None = Field(
        default=None, alias="$schema", description="optional: the JSON Schema of this format, for editors"
    )
    node: str = Field(min_length=1, description="the middleware node this manifest describes")
    description: str = Field(default="", description="free text about the node (not shown to the model)")
    tools: tuple[ToolDecl, ...] = Field(default=(), description="RPCs and actions exposed as tools")
    snapshots: tuple[SnapshotDecl, ...] = Field(default=(), description="topics exposed as snapshot tools")
