"""Turn pydantic's validation errors on a manifest into `ManifestError`s that say what to fix."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ValidationError
from pydantic_core import ErrorDetails

from robovoice.errors import ManifestError
from robovoice.manifest.errors import Loc, describe_json, did_you_mean, json_path
from robovoice.manifest.model import Manifest, SnapshotDecl, ToolAnnotations, ToolDecl

NAME_RULE = "1 to 64 characters: letters, digits, '_' or '-', starting with a letter (e.g. 'navigate_to')"

_EXPECTED = {
    "string_type": "a string",
    "float_type": "a number",
    "int_type": "an integer",
    "bool_type": "true or false",
    "dict_type": "an object",
    "tuple_type": "an array",
    "list_type": "an array",
    "model_type": "an object",
    "model_attributes_type": "an object",
}

_EXAMPLES = {
    "tools": '{"name": "stop_robot", "rpc": "stop", "description": "Stop all motion now."}',
    "snapshots": '{"name": "get_battery_state", "topic": "battery", "description": "...", "max_age_s": 5}',
}

_SUB_MODELS: dict[tuple[type[BaseModel], str], type[BaseModel]] = {
    (Manifest, "tools"): ToolDecl,
    (Manifest, "snapshots"): SnapshotDecl,
    (ToolDecl, "annotations"): ToolAnnotations,
}


def field_names(model: type[BaseModel]) -> list[str]:
    """The JSON spellings (aliases) of a model's fields."""
    return [f.alias or name for name, f in model.model_fields.items()]


def model_at(loc: Loc) -> type[BaseModel] | None:
    """Which manifest model describes the object at `loc` (None inside free-form dicts)."""
    model: type[BaseModel] | None = Manifest
    for item in loc:
        if model is None:
            return None
        if isinstance(item, int):
            continue
        model = _SUB_MODELS.get((model, item))
    return model


def _describe_model(model: type[BaseModel] | None) -> str:
    return {Manifest: "the manifest", ToolDecl: "a tool", SnapshotDecl: "a snapshot",
            ToolAnnotations: "tool annotations"}.get(model, "this object") if model else "this object"


def translate(exc: ValidationError, source: str) -> list[ManifestError]:
    """One `ManifestError` per pydantic error, with a concrete fix."""
    return [_one(err, source) for err in exc.errors(include_url=False)]


def _one(err: ErrorDetails, source: str) -> ManifestError:
    loc: Loc = tuple(err["loc"])
    path = json_path(loc)
    kind = err["type"]
    value: Any = err.get("input")
    ctx: dict[str, Any] = dict(err.get("ctx") or {})
    field = loc[-1] if loc else "$"

    if kind == "extra_forbidden":
        parent = model_at(loc[:-1])
        known = field_names(parent) if parent else []
        return ManifestError(
            source, path, f"unknown field {field!r} in {_describe_model(parent)}",
            did_you_mean(str(field), known, what="fields") + "; remove it or correct the spelling",
        )
    if kind == "missing":
        parent = model_at(loc[:-1])
        return ManifestError(
            source, path, f"missing required field {field!r} in {_describe_model(parent)}",
            f"add {field!r}; required fields: {', '.join(_required(parent))}",
        )
    if kind == "string_pattern_mismatch" and field == "name":
        return ManifestError(source, path, f"invalid tool name {value!r}", f"use {NAME_RULE}")
    if kind == "string_too_short":
        return ManifestError(source, path, f"{field!r} must not be empty", f"give {field!r} a value")
    if kind in {"greater_than", "greater_than_equal"}:
        bound = ctx.get("gt", ctx.get("ge"))
        return ManifestError(
            source, path, f"{field!r} must be greater than {bound}, got {value!r}",
            f"use a positive number of seconds, e.g. {field!r}: 2.0",
        )
    if kind in _EXPECTED:
        expected = _EXPECTED[kind]
        if kind in {"model_type", "model_attributes_type"} and not loc:
            return ManifestError(
                source, path, f"a manifest must be a JSON object, got {describe_json(value)}",
                'write {"node": "<node name>", "tools": [...], "snapshots": [...]}',
            )
        if isinstance(field, int) and len(loc) >= 2:
            return ManifestError(
                source, path, f"each entry of {loc[-2]!r} must be {expected}, got {describe_json(value)}",
                f"write {_describe_model(model_at(loc))} as a JSON object, "
                f"e.g. {_EXAMPLES.get(str(loc[-2]), '{}')}",
            )
        return ManifestError(
            source, path, f"{field!r} must be {expected}, got {describe_json(value)}",
            f"write {field!r} as {expected}" + (" (JSON true/false, not a string)" if kind == "bool_type"
                                                else ""),
        )
    return ManifestError(source, path, f"{err['msg']} (got {describe_json(value)})", "see docs/manifest.md")


def _required(model: type[BaseModel] | None) -> list[str]:
    if model is None:
        return []
    return [f.alias or name for name, f in model.model_fields.items() if f.is_required()]
