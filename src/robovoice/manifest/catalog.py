"""The tool catalog: the union of the surfaces of the nodes present now.

Tool names are one namespace across all nodes. When two nodes declare the same name, the
node that arrived first keeps it and the later declaration is rejected with an error
naming both sources. A tool already offered to clients is therefore never replaced by a
newcomer; when its node leaves, the next claimant (in arrival order) gets the name.

`update` is what the MCP server calls on presence events: it rebuilds an index over the
(few dozen) entries, so `tools()` and `lookup()` are a list copy and a dict look-up.
"""

from __future__ import annotations

from robovoice.errors import ManifestError
from robovoice.manifest.errors import sort_errors
from robovoice.manifest.resolve import CatalogEntry, NodeSurface


class ToolCatalog:
    """Tools and snapshots of the present nodes, by unique name."""

    def __init__(self) -> None:
        self._surfaces: dict[str, NodeSurface] = {}  # insertion order = arrival order
        self._by_name: dict[str, CatalogEntry] = {}
        self._ordered: list[CatalogEntry] = []
        self._errors: list[ManifestError] = []
        self._revision = 0

    @property
    def revision(self) -> int:
        """Increases whenever the list of tools changes (for ``tools/list_changed``)."""
        return self._revision

    def update(self, node: str, surface: NodeSurface | None) -> bool:
        """Set (or, with None, remove) the surface of `node`. Returns whether the tool
        list changed. A node that re-announces keeps its place in the arrival order."""
        if surface is None:
            if self._surfaces.pop(node, None) is None:
                return False
        else:
            if surface.node != node:
                raise ValueError(f"surface of node {surface.node!r} given for node {node!r}")
            self._surfaces[node] = surface
        before = self._ordered
        self._rebuild()
        changed = before != self._ordered
        if changed:
            self._revision += 1
        return changed

    def nodes(self) -> list[str]:
        return list(self._surfaces)

    def surface(self, node: str) -> NodeSurface | None:
        return self._surfaces.get(node)

    def tools(self) -> list[CatalogEntry]:
        """Every exposed tool and snapshot, sorted by name."""
        return list(self._ordered)

    def lookup(self, name: str) -> CatalogEntry | None:
        """The entry exposed under `name`, or None when no present node offers it."""
        return self._by_name.get(name)

    def __contains__(self, name: object) -> bool:
        return name in self._by_name

    def __len__(self) -> int:
        return len(self._ordered)

    def errors(self) -> list[ManifestError]:
        """The problems of the present nodes' manifests, and cross-node name clashes."""
        return list(self._errors)

    def _rebuild(self) -> None:
        by_name: dict[str, CatalogEntry] = {}
        errors: list[ManifestError] = []
        for surface in self._surfaces.values():
            errors.extend(surface.errors)
            for entry in surface.entries:
                first = by_name.get(entry.name)
                if first is None:
                    by_name[entry.name] = entry
                    continue
                errors.append(ManifestError(
                    entry.source, f"{entry.path}.name" if entry.path else "$",
                    f"tool name {entry.name!r} of node {entry.node!r} is already taken by node "
                    f"{first.node!r} ({first.source} at {first.path or '$'}); this tool is not exposed",
                    "rename one of the two tools: names must be unique across all nodes",
                ))
        self._by_name = by_name
        self._ordered = sorted(by_name.values(), key=lambda e: e.name)
        self._errors = sort_errors(errors)

