"""Compile manifests with `ros2` blocks into bindings: which ROS 2 interface each tool calls,
the input schema derived from its request/goal type, and how the model's arguments become a
message (renamed fields, tables of named values, fixed fields), checked before anything is sent.

`compile_manifest` is pure (imports the interface types, no ROS graph): the adapter calls it
at start, and the tests and ``check`` tooling can call it on any folder. Each problem is a
`ManifestError` with file, JSON path and fix, like every other manifest error.
"""

from __future__ import annotations

import copy
import string
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from robovoice.errors import InvalidArgumentsError, ManifestError
from robovoice.manifest.errors import ManifestErrors, json_path
from robovoice.manifest.loader import LoadedManifest
from robovoice.manifest.model import SnapshotDecl, ToolDecl
from robovoice.middleware.base import JSON, NodeInfo, RpcInfo, RpcKind
from robovoice.middleware.ros2_schema import ArgumentMap, check_fixed, check_success, field_problem, tool_schema
from robovoice.middleware.ros2_types import (
    TypeNotFoundError,
    field_json,
    field_type,
    import_type,
    to_json,
    to_message,
)

Loc = tuple[str | int, ...]


@dataclass(frozen=True, slots=True)
class ToolBinding:
    """A tool's ROS 2 service or action and how its arguments become the request/goal."""

    key: str
    """The RPC name announced for the tool (the ROS name, ``#tool`` appended when two tools
    bind the same interface differently)."""
    ros_name: str
    type_name: str
    kind: RpcKind
    interface: Any
    request: Any
    response: Any
    feedback: Any | None
    schema: dict[str, Any] = field(hash=False)
    arguments: tuple[ArgumentMap, ...]
    fixed: Mapping[str, JSON]
    success_field: str | None
    feedback_message: str | None

    def build_request(self, args: Mapping[str, JSON]) -> Any:
        """The request/goal message for the model's arguments; `InvalidArgumentsError` (before
        anything is sent) for a wrong type, an out-of-range value or an unknown name."""
        goal: dict[str, Any] = {}
        for path, value in self.fixed.items():
            _put(goal, path, copy.deepcopy(value))
        by_name = {a.name: a for a in self.arguments}
        for name, value in args.items():
            mapping = by_name.get(name)
            if mapping is None:
                raise InvalidArgumentsError(
                    f"unknown argument {name!r}", hint="pass only the arguments the tool's schema lists",
                    details={"argument": name, "known": sorted(by_name)})
            if mapping.choices is not None:
                if not isinstance(value, str) or value not in mapping.choices:
                    raise InvalidArgumentsError(
                        f"{name}: {value!r} is not one of the known names",
                        hint=f"use one of: {', '.join(mapping.choices)}",
                        details={"argument": name, "known": list(mapping.choices)})
                value = copy.deepcopy(mapping.choices[value])
            if mapping.field is None:
                _merge(goal, value)
            else:
                _put(goal, mapping.field, value)
        try:
            return to_message(self.request, goal)
        except ValueError as exc:
            raise InvalidArgumentsError(
                f"{exc}", hint="correct the value: it was not sent to the robot",
                details={"interface": self.ros_name, "type": self.type_name}) from None

    def feedback_text(self, data: Mapping[str, JSON]) -> str:
        if self.feedback_message is None:
            return ""
        try:
            return string.Formatter().vformat(self.feedback_message, (), _Fields(data))
        except (KeyError, ValueError, TypeError, IndexError):
            return ""


class _Fields(dict[str, Any]):
    def __missing__(self, key: str) -> Any:
        raise KeyError(key)


@dataclass(frozen=True, slots=True)
class SnapshotBinding:
    topic: str
    type_name: str
    message: Any
    fields: tuple[str, ...] | None

    def value(self, msg: Any) -> JSON:
        if self.fields is None:
            return to_json(msg)
        out: dict[str, JSON] = {}
        for path in self.fields:
            current = msg
            for part in path.split("."):
                current = getattr(current, part)
            out[path] = field_json(field_type(self.message, path), current)
        return out


@dataclass(frozen=True, slots=True)
class NodeBinding:
    """One manifest compiled: the node as announced, its tools and snapshots by name."""

    info: NodeInfo
    tools: Mapping[str, ToolBinding]
    snapshots: Mapping[str, SnapshotBinding]

    @property
    def services(self) -> set[str]:
        return {b.ros_name for b in self.tools.values() if b.kind == "rpc"}

    @property
    def actions(self) -> set[str]:
        return {b.ros_name for b in self.tools.values() if b.kind == "action"}

    @property
    def topics(self) -> set[str]:
        return set(self.snapshots)


def compile_manifest(loaded: LoadedManifest) -> NodeBinding:
    """Check every `ros2` block against the installed types; raise `ManifestErrors` with all
    problems, or return the binding and the manifest the MCP server will see."""
    manifest, source = loaded.manifest, loaded.source
    errors: list[ManifestError] = []
    tools: dict[str, ToolBinding] = {}
    announced_tools: list[dict[str, Any]] = []
    for index, decl in enumerate(manifest.tools):
        try:
            binding = _compile_tool(decl, ("tools", index), source)
        except ManifestErrors as exc:
            errors.extend(exc.errors)
            continue
        key = decl.rpc
        same = tools.get(key)
        if same is not None and (same.schema, same.fixed, same.arguments) != (
            binding.schema, binding.fixed, binding.arguments
        ):
            key = f"{decl.rpc}#{decl.name}"
        binding = _with_key(binding, key)
        tools.setdefault(key, binding)
        announced_tools.append(_announced_tool(decl, key, binding.schema))
    snapshots: dict[str, SnapshotBinding] = {}
    for index, snap in enumerate(manifest.snapshots):
        try:
            snapshots[snap.topic] = _compile_snapshot(snap, ("snapshots", index), source)
        except ManifestErrors as exc:
            errors.extend(exc.errors)
    if errors:
        raise ManifestErrors(errors)
    announced = manifest.model_dump(by_alias=True, exclude_none=True, mode="json")
    announced["tools"] = announced_tools
    for snap_json in announced.get("snapshots", []):
        snap_json.pop("ros2", None)
    rpcs = tuple(
        RpcInfo(key, b.kind, tuple(b.schema.get("properties", {})), "") for key, b in tools.items()
    )
    info = NodeInfo(manifest.node, rpcs, tuple(snapshots), announced, source)
    return NodeBinding(info, tools, snapshots)


def _with_key(binding: ToolBinding, key: str) -> ToolBinding:
    from dataclasses import replace

    return replace(binding, key=key)


def _announced_tool(decl: ToolDecl, key: str, schema: dict[str, Any]) -> dict[str, Any]:
    body = decl.model_dump(by_alias=True, exclude_none=True, mode="json")
    body.pop("ros2", None)
    body["rpc"] = key
    body["parameters"] = schema
    return body


def _error(source: str, loc: Loc, message: str, fix: str) -> ManifestErrors:
    return ManifestErrors([ManifestError(source, json_path(loc), message, fix)])


def _import(type_name: str, loc: Loc, source: str) -> Any:
    try:
        return import_type(type_name)
    except TypeNotFoundError as exc:
        raise _error(source, loc, f"unknown ROS 2 type {type_name!r}: {exc.reason}", exc.fix) from None


def _compile_tool(decl: ToolDecl, loc: Loc, source: str) -> ToolBinding:
    binding = decl.ros2
    if binding is None:
        raise _error(source, loc, "a tool of a ros2:// manifest needs a `ros2` block",
                     'add "ros2": {"type": "PACKAGE/srv/Type"} (or …/action/…) naming the type of '
                     f"{decl.rpc!r}")
    if "parameters" in decl.model_fields_set:
        raise _error(source, (*loc, "parameters"), "the parameters of a ROS 2 tool come from its type",
                     "remove `parameters`; rename, describe or hide fields under ros2.arguments, "
                     "ros2.descriptions and ros2.hide")
    if not decl.rpc.startswith("/"):
        raise _error(source, (*loc, "rpc"), f"{decl.rpc!r} is not a ROS 2 service or action name",
                     f"write the full name, e.g. {'/' + decl.rpc!r}")
    type_loc = (*loc, "ros2", "type")
    interface = _import(binding.type, type_loc, source)
    kind: RpcKind = "action" if "/action/" in binding.type else "rpc"
    if "/msg/" in binding.type:
        raise _error(source, type_loc, f"{binding.type} is a message type, not a service or action",
                     "a tool calls a service (…/srv/…) or an action (…/action/…); a topic is a snapshot")
    request = interface.Goal if kind == "action" else interface.Request
    response = interface.Result if kind == "action" else interface.Response
    feedback = interface.Feedback if kind == "action" else None
    problems: list[ManifestError] = []
    fixed = check_fixed(binding, request, (*loc, "ros2"), source, problems)
    schema, arguments = tool_schema(binding, request, (*loc, "ros2"), source, problems)
    if binding.success_field is not None:
        check_success(binding.success_field, response, (*loc, "ros2", "success_field"), source, problems)
    if problems:
        raise ManifestErrors(problems)
    return ToolBinding(decl.rpc, decl.rpc, binding.type, kind, interface, request, response, feedback,
                       schema, arguments, fixed, binding.success_field, binding.feedback_message)


def _compile_snapshot(snap: SnapshotDecl, loc: Loc, source: str) -> SnapshotBinding:
    binding = snap.ros2
    if binding is None:
        raise _error(source, loc, "a snapshot of a ros2:// manifest needs a `ros2` block",
                     'add "ros2": {"type": "PACKAGE/msg/Type"} naming the type of ' f"{snap.topic!r}")
    if not snap.topic.startswith("/"):
        raise _error(source, (*loc, "topic"), f"{snap.topic!r} is not a full ROS 2 topic name",
                     f"write the full name, e.g. {'/' + snap.topic!r}")
    if "/msg/" not in binding.type:
        raise _error(source, (*loc, "ros2", "type"), f"{binding.type} is not a message type",
                     "a topic carries a message type, e.g. sensor_msgs/msg/BatteryState")
    message = _import(binding.type, (*loc, "ros2", "type"), source)
    problems: list[ManifestError] = []
    for index, path in enumerate(binding.fields or ()):
        field_problem(message, path, (*loc, "ros2", "fields", index), source, problems)
    if problems:
        raise ManifestErrors(problems)
    return SnapshotBinding(snap.topic, binding.type, message, binding.fields)


# --- nested dicts by dotted path ---------------------------------------------------------------


def _put(target: dict[str, Any], path: str, value: Any) -> None:
    parts = path.split(".")
    for part in parts[:-1]:
        nxt = target.get(part)
        if not isinstance(nxt, dict):
            nxt = target[part] = {}
        target = nxt
    target[parts[-1]] = value


def _merge(target: dict[str, Any], value: Any) -> None:
    if not isinstance(value, Mapping):
        raise InvalidArgumentsError("a table value without a field must be an object of fields")
    for key, item in value.items():
        if isinstance(item, Mapping) and isinstance(target.get(key), dict):
            _merge(target[key], item)
        else:
            target[key] = copy.deepcopy(item)


__all__ = ["ArgumentMap", "NodeBinding", "SnapshotBinding", "ToolBinding", "compile_manifest"]
