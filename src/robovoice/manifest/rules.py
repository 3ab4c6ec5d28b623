"""Checks on a manifest that its pydantic models cannot express.

They run on the raw JSON (not the model) so that they still report when other parts of
the file failed validation: a file's errors all come out in one pass.

- each tool's `parameters` is a valid JSON Schema (2020-12) of ``type: object``;
- its `required` names only declared `properties`;
- a default for a declared property matches that property's schema;
- tool and snapshot names are unique within the file.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from jsonschema import Draft202012Validator
from jsonschema.exceptions import SchemaError, ValidationError

from robovoice.errors import ManifestError
from robovoice.manifest.errors import Loc, did_you_mean, json_path, nearest

JSON_TYPES = ("string", "number", "integer", "boolean", "object", "array", "null")
SCHEMA_EXAMPLE = '{"type": "object", "properties": {"target": {"type": "string"}}, "required": ["target"]}'


def semantic_errors(data: object, source: str) -> list[ManifestError]:
    """Every semantic problem of the raw manifest `data` (a parsed JSON value)."""
    if not isinstance(data, Mapping):
        return []  # reported by the model validation
    errors: list[ManifestError] = []
    seen: dict[str, str] = {}
    for section in ("tools", "snapshots"):
        entries = data.get(section)
        if not isinstance(entries, list | tuple):
            continue
        for index, entry in enumerate(entries):
            if not isinstance(entry, Mapping):
                continue
            loc: Loc = (section, index)
            errors.extend(_duplicate(entry, loc, seen, source))
            if section == "tools":
                errors.extend(tool_errors(entry, loc, source))
    return errors


def _duplicate(entry: Mapping[str, Any], loc: Loc, seen: dict[str, str], source: str) -> list[ManifestError]:
    name = entry.get("name")
    if not isinstance(name, str):
        return []
    path = json_path((*loc, "name"))
    first = seen.setdefault(name, path)
    if first == path:
        return []
    return [ManifestError(
        source, path, f"duplicate tool name {name!r} (already used at {first})",
        "give every tool and snapshot of the manifest its own name",
    )]


def tool_errors(tool: Mapping[str, Any], loc: Loc, source: str) -> list[ManifestError]:
    """Problems of one tool's `parameters` and `defaults`."""
    params = tool.get("parameters")
    if not isinstance(params, Mapping):
        return []  # absent: the default empty schema; wrong type: reported by the model
    ploc: Loc = (*loc, "parameters")
    errors = schema_errors(params, ploc, source)
    if errors:
        return errors
    properties: Mapping[str, Any] = params.get("properties") or {}
    required = params.get("required") or []
    for index, name in enumerate(required):
        if name not in properties:
            guess = nearest(name, properties)
            fix = (f"did you mean {guess!r}?" if guess else f"add {name!r} to 'properties'") + (
                f" (properties: {', '.join(repr(p) for p in properties) or 'none'})"
            )
            errors.append(ManifestError(
                source, json_path((*ploc, "required", index)),
                f"'required' names {name!r}, which is not in 'properties'", fix,
            ))
    defaults = tool.get("defaults")
    if isinstance(defaults, Mapping):
        for key, value in defaults.items():
            prop = properties.get(key)
            if not isinstance(prop, Mapping | bool):
                continue  # a fixed argument (hidden from the model); checked against the RPC later
            error = _first_violation(prop, value)
            if error is not None:
                errors.append(ManifestError(
                    source, json_path((*loc, "defaults", key)),
                    f"default {value!r} for parameter {key!r} does not match its schema: {error}",
                    f"change the default or the schema at {json_path((*ploc, 'properties', key))}",
                ))
    return errors


def schema_errors(params: Mapping[str, Any], ploc: Loc, source: str) -> list[ManifestError]:
    """`params` must be a valid 2020-12 JSON Schema describing an object."""
    try:
        Draft202012Validator.check_schema(params)
    except SchemaError as exc:
        where = json_path((*ploc, *exc.path))
        if exc.path and exc.path[-1] == "type" and isinstance(exc.instance, str):
            guess = nearest(exc.instance, JSON_TYPES)
            return [ManifestError(
                source, where, f"invalid JSON Schema: {exc.instance!r} is not a JSON Schema type",
                (f"did you mean {guess!r}? " if guess else "") + f"use one of: {', '.join(JSON_TYPES)}",
            )]
        return [ManifestError(
            source, where, f"invalid JSON Schema: {exc.message}",
            f"write a valid JSON Schema (draft 2020-12), e.g. {SCHEMA_EXAMPLE}",
        )]
    kind = params.get("type")
    if kind != "object":
        got = "no 'type'" if kind is None else f"'type': {kind!r}"
        return [ManifestError(
            source, json_path((*ploc, "type")),
            f"'parameters' must describe an object (the arguments), but it has {got}",
            f'set "type": "object" and describe each argument under "properties", e.g. {SCHEMA_EXAMPLE}',
        )]
    unknown = [k for k in params if k not in _KEYWORDS]
    if unknown:
        return [ManifestError(
            source, json_path((*ploc, unknown[0])),
            f"unknown JSON Schema keyword {unknown[0]!r} in 'parameters'",
            did_you_mean(unknown[0], _KEYWORDS, what="keywords") if nearest(unknown[0], _KEYWORDS)
            else "arguments go under 'properties'; " + did_you_mean(unknown[0], _COMMON, what="keywords"),
        )]
    return []


def _first_violation(schema: Mapping[str, Any] | bool, value: object) -> str | None:
    error: ValidationError | None = next(iter(Draft202012Validator(schema).iter_errors(value)), None)
    return None if error is None else error.message


_COMMON = ("type", "properties", "required", "additionalProperties", "description", "title")

# The keywords that may appear at the top of an object schema (2020-12, all vocabularies).
_KEYWORDS = frozenset({
    "$schema", "$id", "$ref", "$defs", "$anchor", "$dynamicRef", "$dynamicAnchor", "$comment",
    "$vocabulary", "type", "properties", "required", "additionalProperties", "patternProperties",
    "propertyNames", "minProperties", "maxProperties", "dependentRequired", "dependentSchemas",
    "unevaluatedProperties", "allOf", "anyOf", "oneOf", "not", "if", "then", "else", "enum", "const",
    "title", "description", "default", "examples", "deprecated", "readOnly", "writeOnly",
})
