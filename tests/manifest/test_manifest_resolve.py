"""`resolve_node`, `manifest_for`, `surface_for`: manifests against live nodes, and the defaults semantics."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest
from jsonschema import Draft202012Validator

from robovoice.manifest import (
    DEFAULT_TIMEOUT_S,
    ManifestErrors,
    NodeSurface,
    load_manifest_dir,
    manifest_for,
    resolve_node,
    surface_for,
    validate_manifest,
)
from robovoice.middleware.base import NodeInfo

SRC = "navigation/mcp.json"


def surface(nav: dict[str, Any], info: NodeInfo) -> NodeSurface:
    return resolve_node(info, validate_manifest(nav, SRC), SRC)


def test_good_manifest_resolves(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    result = surface(nav, nav_info)
    assert result.errors == ()
    assert [e.name for e in result.entries] == ["navigate_to", "return_to_dock", "cancel_navigation",
                                                "get_robot_pose"]
    go, _, cancel = result.tools
    assert (go.node, go.rpc, go.kind, go.timeout_s, go.source, go.path) == (
        "navigation", "navigate", "action", 300.0, SRC, "$.tools[0]")
    assert (cancel.kind, cancel.timeout_s) == ("rpc", 10.0)
    assert DEFAULT_TIMEOUT_S == {"rpc": 10.0, "action": 300.0}
    [pose] = result.snapshots
    assert (pose.topic, pose.max_age_s, pose.node) == ("pose", 1.0, "navigation")
    assert pose.annotations.readOnlyHint is True
    assert pose.input_schema == {"type": "object", "properties": {}, "additionalProperties": False}


def test_explicit_timeout_wins(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["tools"][0]["timeout_s"] = 60
    assert surface(nav, nav_info).tools[0].timeout_s == 60.0


def test_fixed_default_is_hidden_and_always_sent(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    dock = surface(nav, nav_info).tools[1]
    assert dock.input_schema == {"type": "object", "properties": {}, "additionalProperties": False}
    assert dock.fixed == {"target": "charging dock"}
    assert dock.call_arguments({}) == {"target": "charging dock"}
    # even if a client slips the key in, the fixed value is what the RPC gets
    assert dock.call_arguments({"target": "balcony"}) == {"target": "charging dock"}


def test_overridable_default(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["tools"][0]["defaults"] = {"target": "kitchen", "speed": 0.3}
    go = surface(nav, nav_info).tools[0]
    schema = go.input_schema
    assert schema["properties"]["target"]["default"] == "kitchen"
    assert "required" not in schema  # the default makes it optional for the model
    assert schema["additionalProperties"] is False
    assert go.fixed == {"speed": 0.3}
    assert go.call_arguments({}) == {"target": "kitchen", "speed": 0.3}
    assert go.call_arguments({"target": "bedroom"}) == {"target": "bedroom", "speed": 0.3}
    Draft202012Validator.check_schema(schema)
    # the manifest's own parameters are not modified
    assert "default" not in nav["tools"][0]["parameters"]["properties"]["target"]


def test_unknown_rpc_lists_the_offered_ones(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["tools"][0]["rpc"] = "navigte"
    result = surface(nav, nav_info)
    [error] = result.errors
    assert (error.source, error.path) == (SRC, "$.tools[0].rpc")
    assert "node 'navigation' offers no RPC or action 'navigte'" in error.message
    assert "did you mean 'navigate'?" in error.fix
    assert "'cancel', 'navigate', 'set_max_speed'" in error.fix
    # the other declarations survive
    assert [t.name for t in result.tools] == ["return_to_dock", "cancel_navigation"]


def test_parameter_the_rpc_does_not_take(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["tools"][0]["parameters"]["properties"]["place"] = {"type": "string"}
    [error] = surface(nav, nav_info).errors
    assert error.path == "$.tools[0].parameters.properties.place"
    assert "action 'navigate' of node 'navigation' takes no parameter 'place'" in error.message
    assert "'target', 'speed'" in error.fix


def test_default_for_a_parameter_that_does_not_exist(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["tools"][1]["defaults"] = {"targett": "charging dock"}
    [error] = surface(nav, nav_info).errors
    assert error.path == "$.tools[1].defaults.targett"
    assert "takes no such parameter" in error.message
    assert "did you mean 'target'?" in error.fix


def test_rpc_without_parameters(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["tools"][2]["defaults"] = {"now": True}
    [error] = surface(nav, nav_info).errors
    assert error.path == "$.tools[2].defaults.now"
    assert "it takes no arguments" in error.fix


def test_snapshot_topic_not_published(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["snapshots"][0]["topic"] = "poses"
    result = surface(nav, nav_info)
    [error] = result.errors
    assert error.path == "$.snapshots[0].topic"
    assert "publishes no topic 'poses'" in error.message
    assert "did you mean 'pose'?" in error.fix
    assert result.snapshots == ()


def test_manifest_for_another_node(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    result = resolve_node(replace(nav_info, name="base"), validate_manifest(nav, SRC), SRC)
    [error] = result.errors
    assert error.path == "$.node"
    assert result.entries == ()
    with pytest.raises(ManifestErrors):
        result.raise_for_errors()


# --- where the manifest comes from -----------------------------------------------------


def test_announced_manifest(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    info = replace(nav_info, manifest=nav, manifest_source="sim/manifests/navigation/mcp.json")
    loaded = manifest_for(info)
    assert loaded is not None
    assert loaded.source == "sim/manifests/navigation/mcp.json"
    assert loaded.manifest.node == "navigation"


def test_no_manifest_exposes_nothing(nav_info: NodeInfo) -> None:
    assert manifest_for(nav_info) is None
    assert surface_for(nav_info) == NodeSurface("navigation")


def test_bad_announced_manifest(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["tools"][0]["name"] = "go to"
    info = replace(nav_info, manifest=nav)
    with pytest.raises(ManifestErrors) as caught:
        manifest_for(info)
    assert caught.value.source == "<manifest announced by node 'navigation'>"
    result = surface_for(info)
    assert result.entries == () and result.errors[0].path == "$.tools[0].name"


def test_override_folder_wins(tmp_path: Path, nav: dict[str, Any], nav_info: NodeInfo) -> None:
    override = dict(nav, tools=nav["tools"][:1], snapshots=[])
    (tmp_path / "navigation").mkdir()
    (tmp_path / "navigation" / "mcp.json").write_text(json.dumps(override))
    folder = load_manifest_dir(tmp_path)
    info = replace(nav_info, manifest=nav)
    loaded = manifest_for(info, folder)
    assert loaded is not None and loaded.source == str(tmp_path / "navigation" / "mcp.json")
    assert [e.name for e in surface_for(info, folder).entries] == ["navigate_to"]
    # a node the folder does not cover keeps its own manifest
    other = replace(info, name="base", manifest=dict(nav, node="base"))
    assert manifest_for(other, folder) is not None


def test_broken_override_is_reported_not_skipped(tmp_path: Path, nav: dict[str, Any],
                                                  nav_info: NodeInfo) -> None:
    (tmp_path / "navigation.mcp.json").write_text("{oops")
    folder = load_manifest_dir(tmp_path)
    info = replace(nav_info, manifest=nav)
    with pytest.raises(ManifestErrors) as caught:
        manifest_for(info, folder)
    assert caught.value.source == str(tmp_path / "navigation.mcp.json")
    result = surface_for(info, folder)
    assert result.entries == ()
    assert result.source == str(tmp_path / "navigation.mcp.json")


def test_entries_are_hashable(nav: dict[str, Any], nav_info: NodeInfo) -> None:
    result = surface(nav, nav_info)
    assert len(set(result.entries)) == 4
