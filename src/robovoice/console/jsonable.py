"""Typed events (assistant and voice pipeline) as JSON objects for the page and the API.

Every event becomes ``{"kind": "<ClassName>", <its fields>}``. Nested dataclasses, mappings
and tuples are converted; a `TurnResult` keeps only what the page shows (its reply, calls and
latency marks), never callables or audio.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

from robovoice.assistant.loop import TurnResult


def jsonable(value: Any) -> Any:
    """`value` as plain JSON types (dict, list, str, number, bool, None)."""
    if value is None or isinstance(value, bool | int | str):
        return value
    if isinstance(value, float):
        return round(value, 3) if math.isfinite(value) else None
    if isinstance(value, TurnResult):
        return {"reply": value.reply, "calls": jsonable(value.calls), "fell_back": value.fell_back,
                "latency_ms": value.metrics.as_dict()}
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: jsonable(getattr(value, f.name)) for f in dataclasses.fields(value)
                if not callable(getattr(value, f.name))}
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple | set | frozenset):
        return [jsonable(v) for v in value]
    return str(value)


def event_json(event: object) -> dict[str, Any]:
    """One typed event as ``{"kind": ClassName, ...fields}``."""
    body = jsonable(event)
    fields = body if isinstance(body, dict) else {"value": body}
    return {"kind": type(event).__name__, **fields}
