"""Argument validation against a tool's JSON Schema (2020-12), before the middleware sees them."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from jsonschema import Draft202012Validator

from robovoice.errors import InvalidArgumentsError

_MAX_ERRORS = 10


class ArgumentValidator:
    """Validates the arguments of one tool; built once per tool (schema checked then)."""

    def __init__(self, tool: str, schema: Mapping[str, Any]) -> None:
        Draft202012Validator.check_schema(schema)
        self.tool = tool
        self.schema = dict(schema)
        self._validator = Draft202012Validator(self.schema)

    def validate(self, arguments: Mapping[str, Any]) -> None:
        """Raise `InvalidArgumentsError` naming every problem (up to 10) and the schema."""
        errors = sorted(self._validator.iter_errors(dict(arguments)), key=lambda e: list(e.absolute_path))
        if not errors:
            return
        listed = [{"path": e.json_path, "message": e.message} for e in errors[:_MAX_ERRORS]]
        first = listed[0]
        raise InvalidArgumentsError(
            f"invalid arguments for {self.tool}: {first['path']}: {first['message']}",
            hint="call the tool again with arguments that match its input schema (see details.schema)",
            details={"errors": listed, "schema": self.schema},
        )
