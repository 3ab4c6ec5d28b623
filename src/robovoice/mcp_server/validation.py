"""Argument validation against a tool's JSON Schema (2020-12), before the middleware sees them."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from jsonschema import Draft202012Validator

from robovoice.errors import InvalidArgumentsError

_MAX_ERRORS = 10
_REMEMBERED = 256
"""Argument sets known valid, per tool: a voice robot hears the same few requests again and again, and
jsonschema's walk costs ~10 x the JSON encoding that recognises a repeat (the schema never changes)."""


class ArgumentValidator:
    """Validates the arguments of one tool; built once per tool (schema checked then)."""

    def __init__(self, tool: str, schema: Mapping[str, Any]) -> None:
        Draft202012Validator.check_schema(schema)
        self.tool = tool
        self.schema = dict(schema)
        self._validator = Draft202012Validator(self.schema)
        self._valid: dict[str, None] = {}

    def validate(self, arguments: Mapping[str, Any]) -> None:
        """Raise `InvalidArgumentsError` naming every problem (up to 10) and the schema."""
        key = _key(arguments)
        if key is not None and key in self._valid:
            return
        errors = sorted(self._validator.iter_errors(dict(arguments)), key=lambda e: list(e.absolute_path))
        if not errors:
            if key is not None:
                if len(self._valid) >= _REMEMBERED:
                    del self._valid[next(iter(self._valid))]  # the oldest
                self._valid[key] = None
            return
        listed = [{"path": e.json_path, "message": e.message} for e in errors[:_MAX_ERRORS]]
        first = listed[0]
        raise InvalidArgumentsError(
            f"invalid arguments for {self.tool}: {first['path']}: {first['message']}",
            hint="call the tool again with arguments that match its input schema (see details.schema)",
            details={"errors": listed, "schema": self.schema},
        )


def _key(arguments: Mapping[str, Any]) -> str | None:
    """A canonical text of JSON arguments; None for values JSON cannot hold exactly (never remembered).
    JSON keeps true, 1 and 1.0 apart, as the schema's types do."""
    try:
        return json.dumps(arguments, sort_keys=True, allow_nan=False, separators=(",", ":"))
    except (TypeError, ValueError):
        return None
