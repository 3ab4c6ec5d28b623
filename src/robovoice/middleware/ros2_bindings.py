"""Compile manifests with `ros2` blocks into bindings: which ROS 2 interface each tool calls,
the input schema derived from its request/goal type, and how the model's arguments become a
message (renamed fields, tables of named values, fixed fields), checked before anything is sent.

`compile_manifest` is pure (imports the interface types, no ROS graph): the adapter calls it
at start, and the tests and ``check`` tooling can call it on any folder. Each problem is a
`ManifestError` with file, JSON path and fix, like every other manifest error.
"""

from __future__ import annotations

import contextlib
import copy
import string
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from robovoice.errors import InvalidArgumentsError, ManifestError
from robovoice.manifest.errors import ManifestErrors, did_you_mean, json_path
from robovoice.manifest.loader import LoadedManifest
from robovoice.manifest.model import SnapshotDecl, ToolDecl
from robovoice.manifest.ros2_model import Ros2Argument, Ros2ToolBinding
from robovoice.middleware.base import JSON, NodeInfo, RpcInfo, RpcKind
from robovoice.middleware.ros2_types import (
    TypeNotFoundError,
    convert,
    field_json,
    field_names,
    field_type,
    import_type,
    message_schema,
    to_json,
    to_message,
    type_schema,
)

Loc = tuple[str | int, ...]


@dataclass(frozen=True, slots=True)
class ArgumentMap:
    """One LLM-facing argument → the request/goal field it sets."""

    name: str
    field: str | None
    choices: Mapping[str, JSON] | None = None


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
    fixed = _check_fixed(binding, request, (*loc, "ros2"), source, problems)
    schema, arguments = _schema(binding, request, (*loc, "ros2"), source, problems)
    if binding.success_field is not None:
        _check_success(binding.success_field, response, (*loc, "ros2", "success_field"), source, problems)
    if problems:
        raise ManifestErrors(problems)
    return ToolBinding(decl.rpc, decl.rpc, binding.type, kind, interface, request, response, feedback,
                       schema, arguments, fixed, binding.success_field, binding.feedback_message)


def _field(request: Any, path: str, loc: Loc, source: str, problems: list[ManifestError]) -> Any | None:
    try:
        return field_type(request, path)
    except KeyError as exc:
        missing = str(exc.args[0])
        head = path.rsplit(".", 1)[0] if "." in path else ""
        try:
            owner = field_type(request, head) if head else None
            names = field_names(_class_of(owner)) if owner is not None else field_names(request)
        except (KeyError, TypeError):
            names = []
        problems.append(ManifestError(
            source, json_path(loc), f"{_type_label(request)} has no field {path!r} ({missing!r} is unknown)",
            did_you_mean(missing, names, what="fields"),
        ))
        return None


def _class_of(t: Any) -> Any:
    import importlib

    return getattr(importlib.import_module(".".join(t.namespaces)), t.name)


def _type_label(cls: Any) -> str:
    module = cls.__module__.split(".")
    return f"{module[0]}/{module[1]}/{cls.__name__}"


def _check_fixed(binding: Ros2ToolBinding, request: Any, loc: Loc, source: str,
                 problems: list[ManifestError]) -> dict[str, JSON]:
    for path, value in binding.fixed.items():
        t = _field(request, path, (*loc, "fixed", path), source, problems)
        if t is not None:
            try:
                convert(t, value, path)
            except ValueError as exc:
                problems.append(ManifestError(source, json_path((*loc, "fixed", path)), str(exc),
                                              "give a value of the field's type and range"))
    return dict(binding.fixed)


def _schema(binding: Ros2ToolBinding, request: Any, loc: Loc, source: str,
            problems: list[ManifestError]) -> tuple[dict[str, Any], tuple[ArgumentMap, ...]]:
    if binding.arguments is None:
        schema = message_schema(request)
        for index, path in enumerate(binding.hide):
            if _field(request, path, (*loc, "hide", index), source, problems) is not None:
                _drop(schema, path)
        for path in binding.fixed:
            with contextlib.suppress(KeyError):  # a field the type lacks: reported by _check_fixed
                _drop(schema, path)
        for path, text in binding.descriptions.items():
            if _field(request, path, (*loc, "descriptions", path), source, problems) is not None:
                _describe(schema, path, text)
        return schema, tuple(ArgumentMap(name, name) for name in schema["properties"])
    props: dict[str, Any] = {}
    maps: list[ArgumentMap] = []
    for name, arg in binding.arguments.items():
        arg_loc = (*loc, "arguments", name)
        prop = _argument_schema(arg, request, arg_loc, source, problems)
        if prop is not None:
            props[name] = prop
            maps.append(ArgumentMap(name, arg.field, arg.choices))
    required = [a.name for a in maps]  # named on purpose: the model gives them (or `defaults` does)
    schema = {"type": "object", "properties": props, "additionalProperties": False}
    if required:
        schema["required"] = required
    return schema, tuple(maps)


def _argument_schema(arg: Ros2Argument, request: Any, loc: Loc, source: str,
                     problems: list[ManifestError]) -> dict[str, Any] | None:
    t = None
    if arg.field is not None:
        t = _field(request, arg.field, (*loc, "field"), source, problems)
        if t is None:
            return None
    if arg.choices is None:
        if t is None:
            problems.append(ManifestError(source, json_path(loc), "an argument needs a `field` or `choices`",
                                          'add "field": "<request field>" or a "choices" table'))
            return None
        prop = type_schema(t)
    else:
        for choice, value in arg.choices.items():
            try:
                if t is not None:
                    convert(t, value, arg.field or choice)
                else:
                    to_message(request, value)
            except ValueError as exc:
                problems.append(ManifestError(source, json_path((*loc, "choices", choice)), str(exc),
                                              "give a value of the field's type (an object of fields without "
                                              "`field`)"))
        prop = {"type": "string", "enum": list(arg.choices)}
    if arg.description is not None:
        prop["description"] = arg.description
    return prop


def _check_success(path: str, response: Any, loc: Loc, source: str, problems: list[ManifestError]) -> None:
    t = _field(response, path, loc, source, problems)
    if t is not None and getattr(t, "typename", None) != "boolean":
        problems.append(ManifestError(source, json_path(loc), f"{path!r} is not a boolean field",
                                      "name a boolean field of the response/result, e.g. success"))


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
        _field(message, path, (*loc, "ros2", "fields", index), source, problems)
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


def _drop(schema: dict[str, Any], path: str) -> None:
    parts = path.split(".")
    for part in parts[:-1]:
        schema = schema["properties"][part]
    schema["properties"].pop(parts[-1], None)


def _describe(schema: dict[str, Any], path: str, text: str) -> None:
    parts = path.split(".")
    for part in parts[:-1]:
        schema = schema["properties"][part]
    prop = schema["properties"].get(parts[-1])
    if isinstance(prop, dict):
        prop["description"] = text


__all__ = ["ArgumentMap", "NodeBinding", "SnapshotBinding", "ToolBinding", "compile_manifest"]
