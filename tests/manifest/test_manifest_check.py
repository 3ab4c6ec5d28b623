"""`check_manifest_dir`: the report behind `robovoice check-manifests DIR`."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from robovoice.manifest import check_manifest_dir, format_error
from robovoice.middleware.base import NodeInfo, RpcInfo


def write(path: Path, data: Any) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(data if isinstance(data, str) else json.dumps(data), encoding="utf-8")


def stop_manifest(node: str) -> dict[str, Any]:
    return {"node": node, "tools": [{"name": "stop_robot", "rpc": "stop", "description": "Stop now."}]}


def test_good_folder(tmp_path: Path, nav: dict[str, Any]) -> None:
    write(tmp_path / "navigation" / "mcp.json", nav)
    write(tmp_path / "base" / "mcp.json", stop_manifest("base"))
    report = check_manifest_dir(tmp_path)
    assert report.ok
    assert report.errors == ()
    assert report.tools == (
        "cancel_navigation", "get_robot_pose", "navigate_to", "return_to_dock", "stop_robot"
    )
    assert len(report.files) == 2
    assert report.lines()[-1].endswith("2 manifest file(s), 5 tool(s): OK")


def test_errors_are_listed_one_per_line(tmp_path: Path, nav: dict[str, Any]) -> None:
    nav["tools"][0]["default"] = {}
    write(tmp_path / "navigation" / "mcp.json", nav)
    write(tmp_path / "projector.mcp.json", "{")
    report = check_manifest_dir(tmp_path)
    assert not report.ok
    lines = report.lines()
    assert lines[: len(report.errors)] == [format_error(e) for e in report.errors]
    assert lines[0] == (
        f"{tmp_path / 'navigation' / 'mcp.json'}: $.tools[0].default: unknown field 'default' in a tool "
        "(fix: did you mean 'defaults'? (known fields: 'annotations', 'defaults', 'description', 'for_model', "
        "'name', 'parameters', 'ros2', 'rpc', 'timeout_s', 'voice'); remove it or correct the spelling)"
    )
    assert lines[1].startswith(f"{tmp_path / 'projector.mcp.json'}: $: malformed JSON at line 1, column 2")
    assert lines[-1].endswith(": 2 errors")


def test_duplicates_across_the_folder(tmp_path: Path) -> None:
    write(tmp_path / "base" / "mcp.json", stop_manifest("base"))
    write(tmp_path / "navigation" / "mcp.json", stop_manifest("navigation"))
    report = check_manifest_dir(tmp_path)
    [error] = report.errors
    assert error.source == str(tmp_path / "navigation" / "mcp.json")
    assert "already taken by node 'base'" in error.message


def test_against_live_nodes(tmp_path: Path, nav: dict[str, Any], nav_info: NodeInfo) -> None:
    nav["tools"][0]["rpc"] = "drive"
    write(tmp_path / "navigation" / "mcp.json", nav)
    write(tmp_path / "base" / "mcp.json", stop_manifest("base"))
    report = check_manifest_dir(tmp_path, {"navigation": nav_info})
    [error] = report.errors
    assert error.path == "$.tools[0].rpc"
    assert "offers no RPC or action 'drive'" in error.message
    assert any("node 'base' is not running" in note for note in report.notes)
    assert "navigate_to" not in report.tools
    base = NodeInfo("base", (RpcInfo("stop"),))
    assert "stop_robot" in check_manifest_dir(tmp_path, {"navigation": nav_info, "base": base}).tools


def test_empty_folder_is_ok_with_a_note(tmp_path: Path) -> None:
    report = check_manifest_dir(tmp_path)
    assert report.ok and report.files == ()
    assert any("no manifests found" in n for n in report.notes)


def test_missing_folder_fails(tmp_path: Path) -> None:
    report = check_manifest_dir(tmp_path / "nope")
    assert not report.ok


def test_the_sim_robots_manifests_pass() -> None:
    sim = Path(__file__).resolve().parents[2] / "src" / "robovoice" / "sim" / "manifests"
    report = check_manifest_dir(sim)
    assert report.ok, "\n".join(report.lines())
    assert {"navigate_to", "return_to_dock", "get_battery_state", "get_camera_image"} <= set(report.tools)
