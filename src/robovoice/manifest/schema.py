"""The JSON Schema of the manifest format itself, generated from the pydantic models.

The shipped copy, ``manifest.schema.json`` beside this module, lets editors validate and
complete ``mcp.json`` files (``"$schema": "<path>/manifest.schema.json"``). A test keeps it
equal to `manifest_json_schema()`; after changing the models, regenerate it with::

    python -m robovoice.manifest.schema --write
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from robovoice.manifest.model import Manifest

SCHEMA_PATH = Path(__file__).with_name("manifest.schema.json")
SCHEMA_ID = "https://robovoice.dev/schemas/manifest.schema.json"


def manifest_json_schema() -> dict[str, Any]:
    """The manifest format as a JSON Schema (draft 2020-12)."""
    schema = Manifest.model_json_schema(by_alias=True, mode="validation")
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": SCHEMA_ID,
        **schema,
        "title": "robovoice node manifest (mcp.json)",
    }


def render() -> str:
    """The schema file's exact text."""
    return json.dumps(manifest_json_schema(), indent=2, sort_keys=False, ensure_ascii=False) + "\n"


def shipped_schema() -> dict[str, Any]:
    """The schema file shipped with the package."""
    loaded: dict[str, Any] = json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))
    return loaded


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Print or write the manifest JSON Schema.")
    parser.add_argument("--write", action="store_true", help=f"write it to {SCHEMA_PATH}")
    args = parser.parse_args(argv)
    if args.write:
        SCHEMA_PATH.write_text(render(), encoding="utf-8")
    else:
        sys.stdout.write(render())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
