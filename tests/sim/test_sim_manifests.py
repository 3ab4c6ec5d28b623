"""The sim robot's manifests give exactly the tool surface of DESIGN.md section 5."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from robovoice.manifest import check_manifest_dir
from robovoice.manifest.model import Manifest, SnapshotDecl, ToolDecl
from robovoice.middleware.memory import MemoryMiddleware
from robovoice.sim import NODE_NAMES
from robovoice.sim.node import manifest_path

from .sim_testkit import StartRobot

MANIFEST_DIR = Path(manifest_path("navigation")).parent.parent

# DESIGN.md section 5: tool -> its argument names (snapshots take none)
TOOLS: dict[str, set[str]] = {
    "navigate_to": {"target"},
    "get_navigation_targets": set(),
    "cancel_navigation": set(),
    "return_to_dock": set(),
    "stop_robot": set(),
    "set_projector_power": {"on"},
    "start_video_call": {"contact"},
    "end_video_call": set(),
    "list_contacts": set(),
}
SNAPSHOTS: dict[str, tuple[str, float]] = {  # name -> (topic, max_age_s)
    "get_battery_state": ("battery", 3),
    "get_robot_pose": ("pose", 1),
    "get_camera_image": ("camera", 2),
}
# Tools for people and programs (the console's map and status), marked "for_model": false:
# MCP lists them, the model never sees them.
OPERATOR_TOOLS = {"get_map": "navigation", "get_call_state": "communication", "get_projector_state": "projector"}


def _manifests() -> dict[str, Manifest]:
    return {node: Manifest.model_validate(json.loads(Path(manifest_path(node)).read_text()))
            for node in NODE_NAMES}


def test_one_valid_manifest_per_node() -> None:
    manifests = _manifests()
    assert sorted(p.parent.name for p in MANIFEST_DIR.glob("*/mcp.json")) == sorted(NODE_NAMES)
    for node, manifest in manifests.items():
        assert manifest.node == node
        assert manifest.description


def _declared(manifest: Manifest) -> list[ToolDecl | SnapshotDecl]:
    return [*manifest.tools, *manifest.snapshots]


def test_exactly_the_design_tool_surface() -> None:
    operator = {d.name: node for node, m in _manifests().items() for d in _declared(m) if not d.for_model}
    assert operator == OPERATOR_TOOLS
    tools = {t.name: t for m in _manifests().values() for t in m.tools if t.for_model}
    snapshots = {s.name: s for m in _manifests().values() for s in m.snapshots if s.for_model}
    assert {name: set(t.parameters.get("properties", {})) for name, t in tools.items()} == TOOLS
    assert {name: (s.topic, s.max_age_s) for name, s in snapshots.items()} == SNAPSHOTS
    for tool in tools.values():
        params = tool.parameters
        assert params["type"] == "object" and params["additionalProperties"] is False
        assert set(params.get("required", [])) == set(params.get("properties", {}))
        annotations = tool.annotations
        assert annotations.destructiveHint is False and annotations.openWorldHint is False
        assert annotations.readOnlyHint is (tool.name in {"get_navigation_targets", "list_contacts"})
        assert annotations.idempotentHint is not None and annotations.title
        assert len(tool.description) > 40
    assert tools["set_projector_power"].parameters["properties"]["on"]["type"] == "boolean"
    for name in ("navigate_to", "start_video_call"):
        (prop,) = tools[name].parameters["properties"].values()
        assert prop["type"] == "string"
    # return_to_dock is the same drive action with the target fixed by the manifest
    assert tools["return_to_dock"].rpc == tools["navigate_to"].rpc == "drive_to"
    assert tools["return_to_dock"].defaults == {"target": "charging dock"}
    for place in ("kitchen", "living room", "bedroom", "bathroom", "hallway", "front door", "charging dock",
                  "balcony"):
        assert place in tools["navigate_to"].description
    for contact in ("Anna", "Ben", "Clara", "Dr. Weber"):
        assert contact in tools["start_video_call"].description


async def test_manifests_match_the_live_nodes(bus: MemoryMiddleware, start: StartRobot) -> None:
    await start()
    nodes = bus.nodes()
    assert sorted(nodes) == sorted(NODE_NAMES)
    for node, manifest in _manifests().items():
        info = nodes[node]
        assert info.manifest == json.loads(Path(manifest_path(node)).read_text())
        assert info.manifest_source == manifest_path(node)
        for tool in manifest.tools:
            rpc = info.rpc(tool.rpc)
            assert rpc is not None, tool.name
            assert set(tool.parameters.get("properties", {})) | set(tool.defaults) <= set(rpc.params)
        for snapshot in manifest.snapshots:
            assert snapshot.topic in info.topics
    report = check_manifest_dir(MANIFEST_DIR, nodes)
    assert report.ok, report.lines()
    assert sorted(report.tools) == sorted([*TOOLS, *SNAPSHOTS, *OPERATOR_TOOLS])


@pytest.mark.parametrize("node", NODE_NAMES)
async def test_node_info_names_rpcs_with_params_and_kinds(bus: MemoryMiddleware, start: StartRobot,
                                                          node: str) -> None:
    await start(nodes=[node])
    info = bus.nodes()[node]
    assert info.name == node
    for rpc in info.rpcs:
        assert rpc.kind in ("rpc", "action") and rpc.description
    if node == "navigation":
        drive = info.rpc("drive_to")
        assert drive is not None and drive.kind == "action" and drive.params == ("target",)
