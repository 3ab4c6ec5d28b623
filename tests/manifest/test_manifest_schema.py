"""The shipped JSON Schema of the format matches the models; the documented example works."""

from __future__ import annotations

import copy
import json
import re
from pathlib import Path
from typing import Any

import pytest
from jsonschema import Draft202012Validator

from robovoice.manifest import resolve_node, validate_manifest
from robovoice.manifest.schema import SCHEMA_PATH, main, manifest_json_schema, render, shipped_schema
from robovoice.middleware.base import NodeInfo, RpcInfo

DOCS = Path(__file__).resolve().parents[2] / "docs" / "manifest.md"


@pytest.fixture(scope="module")
def validator() -> Draft202012Validator:
    return Draft202012Validator(shipped_schema())


def test_shipped_schema_equals_the_models() -> None:
    assert shipped_schema() == manifest_json_schema()
    regenerate = "run: python -m robovoice.manifest.schema --write"
    assert SCHEMA_PATH.read_text(encoding="utf-8") == render(), regenerate


def test_schema_is_valid() -> None:
    Draft202012Validator.check_schema(shipped_schema())


def test_schema_accepts_a_good_manifest(validator: Draft202012Validator, nav: dict[str, Any]) -> None:
    nav["$schema"] = "manifest.schema.json"
    assert list(validator.iter_errors(nav)) == []


@pytest.mark.parametrize(
    ("path", "value"),
    [
        (("tools", 0, "default"), {}),
        (("tools", 0, "name"), "navigate to"),
        (("tools", 0, "timeout_s"), 0),
        (("tools", 0, "parameters", "type"), "array"),
        (("snapshots", 0, "max_age_s"), "1"),
        (("node",), None),
    ],
)
def test_schema_rejects_bad_manifests(validator: Draft202012Validator, nav: dict[str, Any],
                                      path: tuple[Any, ...], value: Any) -> None:
    bad = copy.deepcopy(nav)
    target: Any = bad
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = value
    assert list(validator.iter_errors(bad)), f"schema accepted {path} = {value!r}"


def test_main_writes_and_prints(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                capsys: pytest.CaptureFixture[str]) -> None:
    assert main([]) == 0
    assert json.loads(capsys.readouterr().out) == manifest_json_schema()
    target = tmp_path / "schema.json"
    monkeypatch.setattr("robovoice.manifest.schema.SCHEMA_PATH", target)
    assert main(["--write"]) == 0
    assert target.read_text(encoding="utf-8") == render()


def test_docs_example_is_valid_and_resolves(validator: Draft202012Validator) -> None:
    text = DOCS.read_text(encoding="utf-8")
    block = re.search(r"```json\n(.*?)```", text, re.S)
    assert block is not None
    data = json.loads(block.group(1))
    assert list(validator.iter_errors(data)) == []
    manifest = validate_manifest(data, "docs/manifest.md")
    info = NodeInfo("navigation", (RpcInfo("navigate", "action", ("target",)), RpcInfo("cancel"),
                                   RpcInfo("set_max_speed", params=("speed",))), ("pose",))
    surface = resolve_node(info, manifest, "docs/manifest.md")
    assert surface.errors == ()
    dock = next(t for t in surface.tools if t.name == "return_to_dock")
    assert dock.call_arguments({}) == {"target": "charging dock"}
    assert [t.rpc for t in surface.tools] == ["navigate", "navigate", "cancel"]
