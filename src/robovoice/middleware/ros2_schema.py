"""Input schemas of ROS 2 tools, derived from the request/goal type and shaped by the
manifest's `ros2` block (`arguments`, `hide`, `fixed`, `descriptions`), each problem a
`ManifestError` with its JSON path. Used by `ros2_bindings.compile_manifest`."""

from __future__ import annotations

import contextlib
import importlib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from robovoice.errors import ManifestError
from robovoice.manifest.errors import did_you_mean, json_path
from robovoice.manifest.ros2_model import Ros2Argument, Ros2ToolBinding
from robovoice.middleware.base import JSON
from robovoice.middleware.ros2_types import convert, field_names, field_type, message_schema, to_message, type_schema

Loc = tuple[str | int, ...]


@dataclass(frozen=True, slots=True)
class ArgumentMap:
    """One LLM-facing argument → the request/goal field it sets."""

    name: str
    field: str | None
    choices: Mapping[str, JSON] | None = None


def field_problem(request: Any, path: str, loc: Loc, source: str, problems: list[ManifestError]) -> Any | None:
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

    return getattr(importlib.import_module(".".join(t.namespaces)), t.name)


def _type_label(cls: Any) -> str:
    module = cls.__module__.split(".")
    return f"{module[0]}/{module[1]}/{cls.__name__}"


def check_fixed(binding: Ros2ToolBinding, request: Any, loc: Loc, source: str,
                 problems: list[ManifestError]) -> dict[str, JSON]:
    for path, value in binding.fixed.items():
        t = field_problem(request, path, (*loc, "fixed", path), source, problems)
        if t is not None:
            try:
                convert(t, value, path)
            except ValueError as exc:
                problems.append(ManifestError(source, json_path((*loc, "fixed", path)), str(exc),
                                              "give a value of the field's type and range"))
    return dict(binding.fixed)


def tool_schema(binding: Ros2ToolBinding, request: Any, loc: Loc, source: str,
            problems: list[ManifestError]) -> tuple[dict[str, Any], tuple[ArgumentMap, ...]]:
    if binding.arguments is None:
        schema = message_schema(request)
        for index, path in enumerate(binding.hide):
            if field_problem(request, path, (*loc, "hide", index), source, problems) is not None:
                _drop(schema, path)
        for path in binding.fixed:
            with contextlib.suppress(KeyError):  # a field the type lacks: reported by _check_fixed
                _drop(schema, path)
        for path, text in binding.descriptions.items():
            if field_problem(request, path, (*loc, "descriptions", path), source, problems) is not None:
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
        t = field_problem(request, arg.field, (*loc, "field"), source, problems)
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


def check_success(path: str, response: Any, loc: Loc, source: str, problems: list[ManifestError]) -> None:
    t = field_problem(response, path, loc, source, problems)
    if t is not None and getattr(t, "typename", None) != "boolean":
        problems.append(ManifestError(source, json_path(loc), f"{path!r} is not a boolean field",
                                      "name a boolean field of the response/result, e.g. success"))


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
