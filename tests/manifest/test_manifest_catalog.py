"""`ToolCatalog`: the union of the present nodes' surfaces; cross-node duplicates."""

from __future__ import annotations

from robovoice.manifest import NodeSurface, SnapshotEntry, ToolAnnotations, ToolCatalog, ToolEntry


def tool(name: str, node: str, source: str = "", index: int = 0) -> ToolEntry:
    return ToolEntry(name, node, "do", "rpc", "does it", {"type": "object", "properties": {}}, {},
                     ToolAnnotations(), 10.0, source or f"{node}/mcp.json", f"$.tools[{index}]")


def snap(name: str, node: str) -> SnapshotEntry:
    return SnapshotEntry(name, node, "battery", "battery state", 5.0, f"{node}/mcp.json", "$.snapshots[0]")


def node(name: str, *tools: ToolEntry, snaps: tuple[SnapshotEntry, ...] = ()) -> NodeSurface:
    return NodeSurface(name, f"{name}/mcp.json", tools, snaps)


def test_union_sorted_by_name() -> None:
    catalog = ToolCatalog()
    nav = node("nav", tool("navigate_to", "nav"), tool("cancel_navigation", "nav", index=1))
    base = node("base", tool("stop_robot", "base"), snaps=(snap("get_battery_state", "base"),))
    assert catalog.update("nav", nav)
    assert catalog.update("base", base)
    assert [t.name for t in catalog.tools()] == ["cancel_navigation", "get_battery_state", "navigate_to",
                                                 "stop_robot"]
    assert len(catalog) == 4 and "stop_robot" in catalog
    entry = catalog.lookup("get_battery_state")
    assert isinstance(entry, SnapshotEntry) and entry.topic == "battery"
    assert catalog.lookup("set_max_speed") is None
    assert catalog.errors() == []


def test_leaving_node_takes_its_tools() -> None:
    catalog = ToolCatalog()
    catalog.update("nav", node("nav", tool("navigate_to", "nav")))
    catalog.update("base", node("base", tool("stop_robot", "base")))
    assert catalog.update("nav", None)
    assert [t.name for t in catalog.tools()] == ["stop_robot"]
    assert catalog.lookup("navigate_to") is None
    assert not catalog.update("nav", None)  # already gone: nothing changes


def test_cross_node_duplicate_first_keeps_the_name() -> None:
    catalog = ToolCatalog()
    catalog.update("base", node("base", tool("stop_robot", "base")))
    catalog.update("nav", node("nav", tool("navigate_to", "nav"), tool("stop_robot", "nav", index=1)))
    entry = catalog.lookup("stop_robot")
    assert entry is not None and entry.node == "base"
    [error] = catalog.errors()
    assert (error.source, error.path) == ("nav/mcp.json", "$.tools[1].name")
    assert "already taken by node 'base' (base/mcp.json at $.tools[0])" in error.message
    assert "nav/mcp.json" in error.source and "rename" in error.fix
    assert [t.name for t in catalog.tools()] == ["navigate_to", "stop_robot"]


def test_duplicate_name_passes_on_when_the_holder_leaves() -> None:
    catalog = ToolCatalog()
    catalog.update("base", node("base", tool("stop_robot", "base")))
    catalog.update("nav", node("nav", tool("stop_robot", "nav")))
    catalog.update("base", None)
    entry = catalog.lookup("stop_robot")
    assert entry is not None and entry.node == "nav"
    assert catalog.errors() == []
    # the returning node is now the later one
    catalog.update("base", node("base", tool("stop_robot", "base")))
    entry = catalog.lookup("stop_robot")
    assert entry is not None and entry.node == "nav"
    assert len(catalog.errors()) == 1


def test_reannounce_keeps_arrival_order() -> None:
    catalog = ToolCatalog()
    catalog.update("base", node("base", tool("stop_robot", "base")))
    catalog.update("nav", node("nav", tool("stop_robot", "nav")))
    catalog.update("base", node("base", tool("stop_robot", "base"), tool("dock", "base", index=1)))
    entry = catalog.lookup("stop_robot")
    assert entry is not None and entry.node == "base"
    assert catalog.nodes() == ["base", "nav"]


def test_update_reports_changes_and_revision() -> None:
    catalog = ToolCatalog()
    assert catalog.revision == 0
    assert catalog.update("nav", node("nav", tool("navigate_to", "nav")))
    assert catalog.revision == 1
    assert not catalog.update("nav", node("nav", tool("navigate_to", "nav")))  # same surface again
    assert catalog.revision == 1
    assert not catalog.update("empty", NodeSurface("empty"))
    assert catalog.update("nav", None)
    assert catalog.revision == 2


def test_surface_errors_are_reported() -> None:
    from robovoice.errors import ManifestError

    catalog = ToolCatalog()
    error = ManifestError("nav/mcp.json", "$.tools[0].rpc", "no such RPC", "use another")
    catalog.update("nav", NodeSurface("nav", "nav/mcp.json", errors=(error,)))
    assert catalog.errors() == [error]
    catalog.update("nav", None)
    assert catalog.errors() == []
