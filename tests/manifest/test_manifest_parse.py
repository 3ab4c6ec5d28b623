"""`parse_manifest`: every kind of bad manifest names the file, the JSON path and the fix."""

from __future__ import annotations

import json
from types import MappingProxyType
from typing import Any

import pytest

from robovoice.errors import ConfigError, ManifestError
from robovoice.manifest import ManifestErrors, format_error, parse_manifest, validate_manifest

SRC = "manifests/navigation/mcp.json"


def errors_of(data: Any, source: str = SRC) -> list[ManifestError]:
    text = data if isinstance(data, str) else json.dumps(data, indent=2)
    with pytest.raises(ManifestErrors) as caught:
        parse_manifest(text, source)
    assert all(e.source == source for e in caught.value.errors)
    return list(caught.value.errors)


def only(data: Any) -> ManifestError:
    errors = errors_of(data)
    assert len(errors) == 1, [format_error(e) for e in errors]
    return errors[0]


def test_good_manifest_parses(nav: dict[str, Any]) -> None:
    manifest = parse_manifest(json.dumps(nav), SRC)
    assert manifest.node == "navigation"
    assert [t.name for t in manifest.tools] == ["navigate_to", "return_to_dock", "cancel_navigation"]
    assert manifest.tools[1].defaults == {"target": "charging dock"}
    assert manifest.tools[2].parameters["type"] == "object"  # the default: no arguments
    assert manifest.snapshots[0].max_age_s == 1.0


def test_malformed_json_gives_line_and_column() -> None:
    error = only('{\n  "node": "navigation",\n  "tools": [,]\n}')
    assert error.path == "$"
    assert "line 3, column 13" in error.message
    assert "JSON syntax" in error.fix


def test_empty_file_is_malformed() -> None:
    assert "line 1, column 1" in only("").message


def test_nan_is_rejected() -> None:
    snap = '{"name": "a", "topic": "t", "description": "d", "max_age_s": NaN}'
    error = only('{"node": "n", "snapshots": [' + snap + "]}")
    assert "NaN" in error.message


def test_not_an_object() -> None:
    error = only("[]")
    assert error.path == "$"
    assert "must be a JSON object" in error.message


@pytest.mark.parametrize(
    ("where", "wrong", "right"),
    [
        ((), "snapshot", "snapshots"),
        ((), "tool", "tools"),
        (("tools", 1), "default", "defaults"),
        (("tools", 0), "params", "parameters"),
        (("tools", 0), "timeout", "timeout_s"),
        (("snapshots", 0), "max_age", "max_age_s"),
    ],
)
def test_unknown_field_suggests_the_nearest(nav: dict[str, Any], where: tuple[Any, ...], wrong: str,
                                            right: str) -> None:
    target: Any = nav
    for key in where:
        target = target[key]
    target[wrong] = target.pop(right, 1)
    error = next(e for e in errors_of(nav) if "unknown field" in e.message)
    path = "$" + "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in where) + f".{wrong}"
    assert error.path == path
    assert f"did you mean {right!r}?" in error.fix


def test_unknown_annotation_suggests(nav: dict[str, Any]) -> None:
    nav["tools"][2]["annotations"] = {"readonlyHint": True}
    error = only(nav)
    assert error.path == "$.tools[2].annotations.readonlyHint"
    assert "did you mean 'readOnlyHint'?" in error.fix


@pytest.mark.parametrize(
    ("path", "value", "expected"),
    [
        (("tools", 0, "timeout_s"), "30", "a number"),
        (("tools", 0, "description"), 5, "a string"),
        (("tools", 0, "annotations", "readOnlyHint"), "yes", "true or false"),
        (("tools", 0, "defaults"), ["kitchen"], "an object"),
        (("tools", 0, "parameters"), "string", "an object"),
        (("snapshots", 0, "max_age_s"), "1", "a number"),
        (("node",), 7, "a string"),
    ],
)
def test_wrong_types(nav: dict[str, Any], path: tuple[Any, ...], value: Any, expected: str) -> None:
    target: Any = nav
    for key in path[:-1]:
        target = target.setdefault(key, {}) if isinstance(key, str) else target[key]
    target[path[-1]] = value
    error = only(nav)
    assert error.path == "$" + "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in path)
    assert f"must be {expected}" in error.message
    assert expected in error.fix


def test_tools_must_be_an_array(nav: dict[str, Any]) -> None:
    nav["tools"] = {"navigate_to": {}}
    error = only(nav)
    assert error.path == "$.tools"
    assert error.message == "'tools' must be an array, got an object"


def test_missing_field(nav: dict[str, Any]) -> None:
    del nav["tools"][0]["rpc"]
    error = only(nav)
    assert error.path == "$.tools[0].rpc"
    assert "missing required field 'rpc'" in error.message
    assert "add 'rpc'" in error.fix


def test_non_positive_max_age(nav: dict[str, Any]) -> None:
    nav["snapshots"][0]["max_age_s"] = 0
    error = only(nav)
    assert error.path == "$.snapshots[0].max_age_s"
    assert "greater than 0" in error.message


@pytest.mark.parametrize("name", ["navigate to", "1st_tool", "", "x" * 65, "dock.return"])
def test_invalid_tool_name(nav: dict[str, Any], name: str) -> None:
    nav["tools"][2]["name"] = name
    error = only(nav)
    assert error.path == "$.tools[2].name"
    assert f"invalid tool name {name!r}" in error.message
    assert "letters, digits" in error.fix


def test_invalid_parameters_schema(nav: dict[str, Any]) -> None:
    nav["tools"][0]["parameters"]["properties"]["target"]["type"] = "strin"
    error = only(nav)
    assert error.path == "$.tools[0].parameters.properties.target.type"
    assert error.message == "invalid JSON Schema: 'strin' is not a JSON Schema type"
    assert "did you mean 'string'?" in error.fix


def test_invalid_parameters_schema_in_general(nav: dict[str, Any]) -> None:
    nav["tools"][0]["parameters"]["properties"]["target"]["minLength"] = -1
    error = only(nav)
    assert error.path == "$.tools[0].parameters.properties.target.minLength"
    assert error.message == "invalid JSON Schema: -1 is less than the minimum of 0"
    assert "draft 2020-12" in error.fix


def test_entries_must_be_objects(nav: dict[str, Any]) -> None:
    nav["tools"][1] = "return_to_dock"
    error = only(nav)
    assert error.path == "$.tools[1]"
    assert error.message == "each entry of 'tools' must be an object, got a string ('return_to_dock')"
    assert '"rpc"' in error.fix


@pytest.mark.parametrize(("params", "got"), [({"type": "array"}, "'type': 'array'"), ({}, "no 'type'")])
def test_parameters_must_be_an_object_schema(nav: dict[str, Any], params: dict[str, Any], got: str) -> None:
    nav["tools"][0]["parameters"] = params
    error = only(nav)
    assert error.path == "$.tools[0].parameters.type"
    assert got in error.message
    assert '"type": "object"' in error.fix


def test_argument_outside_properties(nav: dict[str, Any]) -> None:
    nav["tools"][0]["parameters"] = {"type": "object", "target": {"type": "string"}}
    error = only(nav)
    assert error.path == "$.tools[0].parameters.target"
    assert "unknown JSON Schema keyword 'target'" in error.message
    assert "'properties'" in error.fix


def test_required_names_a_missing_property(nav: dict[str, Any]) -> None:
    nav["tools"][0]["parameters"]["required"] = ["target", "targt"]
    error = only(nav)
    assert error.path == "$.tools[0].parameters.required[1]"
    assert "'targt', which is not in 'properties'" in error.message
    assert "did you mean 'target'?" in error.fix


def test_default_must_match_the_property_schema(nav: dict[str, Any]) -> None:
    nav["tools"][0]["defaults"] = {"target": 5}
    error = only(nav)
    assert error.path == "$.tools[0].defaults.target"
    assert "5 is not of type 'string'" in error.message


def test_duplicate_tool_names(nav: dict[str, Any]) -> None:
    nav["tools"][2]["name"] = "navigate_to"
    error = only(nav)
    assert error.path == "$.tools[2].name"
    assert "duplicate tool name 'navigate_to' (already used at $.tools[0].name)" in error.message


def test_snapshot_name_clashes_with_tool(nav: dict[str, Any]) -> None:
    nav["snapshots"][0]["name"] = "return_to_dock"
    error = only(nav)
    assert error.path == "$.snapshots[0].name"
    assert "duplicate tool name" in error.message


def test_duplicate_json_key() -> None:
    error = only('{"node": "a", "tools": [], "node": "b"}')
    assert error.path == "$.node"
    assert "appears more than once" in error.message


def test_all_errors_of_a_file_come_together(nav: dict[str, Any]) -> None:
    nav["tools"][0]["parameters"]["required"] = ["targt"]
    nav["tools"][1]["default"] = nav["tools"][1].pop("defaults")
    nav["tools"][2]["name"] = "bad name"
    nav["snapshots"][0]["max_age_s"] = -1
    errors = errors_of(nav)
    assert [e.path for e in errors] == [
        "$.snapshots[0].max_age_s",
        "$.tools[0].parameters.required[0]",
        "$.tools[1].default",
        "$.tools[2].name",
    ]


def test_error_group_is_a_manifest_error(nav: dict[str, Any]) -> None:
    nav["tools"][2]["name"] = "bad name"
    nav["snapshots"][0]["max_age_s"] = -1
    with pytest.raises(ManifestError) as caught:
        parse_manifest(json.dumps(nav), SRC)
    group = caught.value
    assert isinstance(group, ManifestErrors) and isinstance(group, ConfigError)
    assert (group.source, group.path) == (SRC, group.errors[0].path)
    lines = str(group).splitlines()
    assert lines == [format_error(e) for e in group.errors]
    assert lines[0].startswith(f"{SRC}: $.snapshots[0].max_age_s: ")
    assert lines[0].endswith(")") and "(fix: " in lines[0]


def test_validate_manifest_takes_parsed_json(nav: dict[str, Any]) -> None:
    assert validate_manifest(nav, "announced").node == "navigation"
    nav["tools"][0]["name"] = "a b"
    with pytest.raises(ManifestErrors) as caught:
        validate_manifest(nav, "announced by navigation")
    assert caught.value.source == "announced by navigation"


def test_validate_manifest_takes_any_mapping(nav: dict[str, Any]) -> None:
    frozen = MappingProxyType({**nav, "tools": tuple(MappingProxyType(t) for t in nav["tools"])})
    assert len(validate_manifest(frozen, "announced").tools) == 3


def test_validate_manifest_rejects_non_json_values(nav: dict[str, Any]) -> None:
    nav["tools"][1]["defaults"] = {"target": object()}
    with pytest.raises(ManifestErrors, match="not plain JSON"):
        validate_manifest(nav, "x")
