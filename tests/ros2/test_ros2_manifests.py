"""ROS 2 manifests without a ROS graph: URIs, schemas derived from message types, values
converted and range-checked, and bad manifests reported as file: path: message (fix: ...)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from robovoice.errors import ConfigError, InvalidArgumentsError
from robovoice.manifest import format_error, load_manifest_dir
from robovoice.manifest.errors import ManifestErrors
from robovoice.middleware import open_middleware
from robovoice.middleware.ros2 import Ros2Middleware, load_bindings
from robovoice.middleware.ros2_bindings import NodeBinding, compile_manifest
from robovoice.middleware.ros2_config import Ros2Settings
from robovoice.middleware.ros2_types import import_type, message_schema, to_json, to_message

from .ros2_testkit import MANIFESTS


def test_uri_options_and_unknown_ones() -> None:
    settings = Ros2Settings.from_uri("ros2://?domain_id=42&manifests=/x&discovery=subnet&peers=a,b")
    assert (settings.domain_id, settings.discovery, settings.peers) == (42, "subnet", ("a", "b"))
    assert settings.environment()["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "SUBNET"
    assert Ros2Settings.from_uri("ros2://").environment()["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "LOCALHOST"
    with pytest.raises(ConfigError, match=r"unknown parameter\(s\) domain; known: discovery, domain_id, lease"):
        Ros2Settings.from_uri("ros2://?domain=3")
    for bad in ("ros2://?domain_id=233", "ros2://?domain_id=x", "ros2://?discovery=world", "ros2://host:1"):
        with pytest.raises(ConfigError):
            Ros2Settings.from_uri(bad)
    assert isinstance(open_middleware(f"ros2://?manifests={MANIFESTS}"), Ros2Middleware)


def test_schemas_are_derived_from_the_types() -> None:
    pose = message_schema(import_type("geometry_msgs/msg/PoseWithCovarianceStamped"))
    inner = pose["properties"]["pose"]["properties"]
    assert inner["covariance"] == {"type": "array", "items": {"type": "number"}, "minItems": 36, "maxItems": 36}
    assert pose["properties"]["header"]["properties"]["stamp"]["type"] == "number"  # time as seconds
    battery = message_schema(import_type("sensor_msgs/msg/BatteryState"))["properties"]
    assert battery["power_supply_status"] == {"type": "integer", "minimum": 0, "maximum": 255}
    assert battery["cell_voltage"]["items"] == {"type": "number"}


def test_values_are_converted_and_range_checked() -> None:
    battery = import_type("sensor_msgs/msg/BatteryState")
    msg = to_message(battery, {"voltage": 12, "header": {"stamp": 5.25}})
    assert msg.voltage == 12.0 and (msg.header.stamp.sec, msg.header.stamp.nanosec) == (5, 250_000_000)
    assert to_json(msg)["header"]["stamp"] == 5.25
    for bad, why in (({"voltage": "abc"}, "expected a number"), ({"power_supply_status": 300}, "out of range"),
                     ({"present": 1}, "true or false"), ({"nope": 1}, "no field 'nope'"),
                     ({"cell_voltage": [1, "x"]}, r"cell_voltage\[1\]")):
        with pytest.raises(ValueError, match=why):
            to_message(battery, bad)
    with pytest.raises(ValueError, match="exactly 36 items"):
        to_message(import_type("geometry_msgs/msg/PoseWithCovariance"), {"covariance": [0.0]})


def _bindings() -> dict[str, NodeBinding]:
    loaded = load_manifest_dir(MANIFESTS)
    return {node: compile_manifest(m) for node, m in loaded.manifests.items()}


def test_arguments_map_to_the_request() -> None:
    projector = _bindings()["projector"].tools["/projector/set_power"]
    assert projector.build_request({"on": True}).data is True
    fib = _bindings()["fibonacci"]
    assert set(fib.tools) == {"/fibonacci", "/fibonacci#count_named", "/fibonacci#count_briefly"}  # 3 bindings
    assert fib.tools["/fibonacci#count_named"].build_request({"length": "long"}).order == 30
    with pytest.raises(InvalidArgumentsError, match="not one of the known names"):
        fib.tools["/fibonacci#count_named"].build_request({"length": "huge"})
    with pytest.raises(InvalidArgumentsError, match="out of range"):
        fib.tools["/fibonacci"].build_request({"order": 2**31})


def _write(tmp_path: Path, node: str, manifest: dict[str, Any]) -> Path:
    (tmp_path / f"{node}.mcp.json").write_text(json.dumps(manifest, indent=2))
    return tmp_path


def _errors(tmp_path: Path, node: str, manifest: dict[str, Any]) -> list[str]:
    loaded = load_manifest_dir(_write(tmp_path, node, manifest))
    assert not loaded.errors, loaded.errors
    with pytest.raises(ManifestErrors) as caught:
        compile_manifest(loaded.manifests[node])
    return [format_error(e) for e in caught.value.errors]


def _tool(**ros2: Any) -> dict[str, Any]:
    return {"name": "drive", "rpc": "/navigate", "description": "Drive.", "ros2": ros2}


@pytest.mark.parametrize(("ros2", "path", "words"), [
    ({"type": "nav2_msgz/action/NavigateToPose"}, "$.tools[0].ros2.type",
     "interface package 'nav2_msgz' is not installed"),
    ({"type": "std_srvs/srv/SetBol"}, "$.tools[0].ros2.type", "has no type 'SetBol' (fix: use one of: Empty, SetBool"),
    ({"type": "std_msgs/msg/String"}, "$.tools[0].ros2.type", "a message type, not a service or action"),
    ({"type": "std_srvs/srv/SetBool", "fixed": {"dat": True}}, '$.tools[0].ros2.fixed.dat',
     "has no field 'dat' ('dat' is unknown) (fix: did you mean 'data'?"),
    ({"type": "std_srvs/srv/SetBool", "arguments": {"on": {"field": "value"}}}, "$.tools[0].ros2.arguments.on.field",
     "has no field 'value'"),
    ({"type": "test_msgs/action/Fibonacci", "arguments": {"n": {"field": "order", "choices": {"big": 1e12}}}},
     "$.tools[0].ros2.arguments.n.choices.big", "out of range for int32"),
    ({"type": "std_srvs/srv/SetBool", "success_field": "message"}, "$.tools[0].ros2.success_field",
     "is not a boolean field"),
])
def test_bad_ros2_bindings_are_precise(tmp_path: Path, ros2: dict[str, Any], path: str, words: str) -> None:
    errors = _errors(tmp_path, "robot", {"node": "robot", "tools": [_tool(**ros2)]})
    source = str(tmp_path / "robot.mcp.json")
    assert any(e.startswith(f"{source}: {path}: ") and words in e for e in errors), errors


def test_parameters_and_missing_blocks_are_refused(tmp_path: Path) -> None:
    tool = _tool(type="std_srvs/srv/SetBool")
    tool["parameters"] = {"type": "object", "properties": {"data": {"type": "boolean"}}}
    snapshot = {"name": "battery", "topic": "battery", "description": "b", "max_age_s": 1,
                "ros2": {"type": "sensor_msgs/msg/BatteryState", "fields": ["percentag"]}}
    errors = _errors(tmp_path, "robot", {"node": "robot", "tools": [tool, {
        "name": "plain", "rpc": "/x", "description": "no ros2 block"}], "snapshots": [snapshot]})
    assert any("$.tools[0].parameters: the parameters of a ROS 2 tool come from its type" in e for e in errors)
    assert any("$.tools[1]: a tool of a ros2:// manifest needs a `ros2` block" in e for e in errors)
    assert any("$.snapshots[0].topic: 'battery' is not a full ROS 2 topic name" in e for e in errors)


def test_a_folder_with_only_bad_manifests_is_a_config_error(tmp_path: Path) -> None:
    _write(tmp_path, "robot", {"node": "robot", "tools": [_tool(type="nav2_msgz/action/NavigateToPose")]})
    with pytest.raises(ConfigError, match=r"robot\.mcp\.json: \$\.tools\[0\]\.ros2\.type: unknown ROS 2 type"):
        load_bindings(Ros2Settings.from_uri(f"ros2://?manifests={tmp_path}"))
    _write(tmp_path, "good", {"node": "good", "tools": [
        {"name": "power", "rpc": "/power", "description": "p", "ros2": {"type": "std_srvs/srv/SetBool"}}]})
    assert set(load_bindings(Ros2Settings.from_uri(f"ros2://?manifests={tmp_path}"))) == {"good"}


def test_check_manifests_reports_ros2_problems(tmp_path: Path) -> None:
    from robovoice.manifest.check import check_manifest_dir

    _write(tmp_path, "robot", {"node": "robot", "tools": [_tool(type="std_srvs/srv/SetBool", fixed={"dat": True})]})
    report = check_manifest_dir(tmp_path)
    assert not report.ok and any("$.tools[0].ros2.fixed.dat" in line for line in report.lines())
    assert check_manifest_dir(MANIFESTS).ok
