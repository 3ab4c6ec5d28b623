"""The `ros2` blocks of a manifest: bind a tool or snapshot to a ROS 2 interface the robot
already has (a service, an action, a topic), by name and type, with no robovoice code on the
robot. Read by the `ros2://` middleware adapter (docs/ros2.md); other middlewares ignore them.

A bound tool's ``rpc`` is the ROS 2 service or action name (``/projector/set_power``) and
``ros2.type`` its type (``std_srvs/srv/SetBool``, ``…/action/…``). Its input schema is derived
from the request or goal type; ``ros2.arguments`` (LLM-facing names → fields, or tables of
named values), ``hide``, ``fixed`` and ``descriptions`` shape what the model sees.
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

FIELD_PATH_PATTERN = r"^[A-Za-z][A-Za-z0-9_]*(\.[A-Za-z][A-Za-z0-9_]*)*$"
TYPE_PATTERN = r"^[A-Za-z][A-Za-z0-9_]*/(msg|srv|action)/[A-Z][A-Za-z0-9]*$"


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)


class Ros2Argument(_Strict):
    """One LLM-facing argument: a field of the request/goal under another name, or a table of
    named values (``"kitchen"`` → the kitchen's pose)."""

    field: str | None = Field(
        default=None, pattern=FIELD_PATH_PATTERN,
        description="the request/goal field it sets (dotted path, e.g. pose.pose.position.x); "
        "with `choices` and no field, each choice is an object of fields set at the top level",
    )
    description: str | None = Field(default=None, description="what the argument means, for the model")
    choices: dict[str, Any] | None = Field(
        default=None, min_length=1,
        description="a table: the model passes one of these names, the field gets its value",
    )


class Ros2ToolBinding(_Strict):
    """A tool bound to a ROS 2 service or action (the tool's `rpc` is its name)."""

    type: str = Field(pattern=TYPE_PATTERN, description="the service or action type, e.g. std_srvs/srv/SetBool")
    arguments: dict[str, Ros2Argument] | None = Field(
        default=None,
        description="the arguments the model sees, by LLM-facing name; without it, every field of the "
        "request/goal is an argument under its own name",
    )
    hide: tuple[str, ...] = Field(default=(), description="request/goal fields the model does not see")
    fixed: dict[str, Any] = Field(
        default_factory=dict, description="request/goal fields always sent with these values (hidden)"
    )
    descriptions: dict[str, str] = Field(default_factory=dict, description="descriptions of request/goal fields")
    success_field: str | None = Field(
        default=None, pattern=FIELD_PATH_PATTERN,
        description="a boolean field of the response/result: false makes the call a tool error "
        "(its `message` field, if any, is the error's message)",
    )
    feedback_message: str | None = Field(
        default=None,
        description="how an action's feedback is told as progress, a Python format string over the "
        "feedback's fields, e.g. '{distance_remaining:.1f} m to go'",
    )


class Ros2SnapshotBinding(_Strict):
    """A snapshot bound to a ROS 2 topic (the snapshot's `topic` is its name)."""

    type: str = Field(pattern=TYPE_PATTERN, description="the message type, e.g. sensor_msgs/msg/BatteryState")
    fields: tuple[str, ...] | None = Field(
        default=None, description="only these fields of the message (dotted paths); default: all"
    )


def ros2_problems(manifest: Any, source: str) -> list[Any]:
    """The ROS 2 problems of a manifest with `ros2` blocks (unknown or uninstalled types, fields a
    type lacks, ...) as `ManifestError`s; none for a manifest without such blocks. Checked
    against the interface packages installed here (`robovoice check-manifests`)."""
    if not any(d.ros2 is not None for d in (*manifest.tools, *manifest.snapshots)):
        return []
    from robovoice.errors import ManifestError, MissingDependencyError
    from robovoice.manifest.errors import ManifestErrors
    from robovoice.manifest.loader import LoadedManifest

    try:
        from robovoice.middleware.ros2_bindings import compile_manifest
    except MissingDependencyError as exc:
        return [ManifestError(source, "$", "the manifest binds ROS 2 interfaces, but ROS 2 is not installed here",
                              exc.install)]
    try:
        compile_manifest(LoadedManifest(manifest, source))
    except ManifestErrors as exc:
        return list(exc.errors)
    return []
