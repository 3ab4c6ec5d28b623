"""`robovoice check-manifests DIR`: check a folder of manifests, optionally against live nodes.

Schema-level checks always (JSON syntax, fields and types, tool names, parameter
schemas, duplicates, file layout, names unique across the folder); with `nodes` (the
nodes present on a middleware) also the RPCs, parameters, defaults and topics each
manifest names. The CLI prints `CheckReport.lines()` and exits with ``0 if report.ok else 1``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from robovoice.errors import ManifestError
from robovoice.manifest.catalog import ToolCatalog
from robovoice.manifest.errors import format_error, sort_errors
from robovoice.manifest.loader import load_manifest_dir
from robovoice.manifest.model import Manifest
from robovoice.manifest.resolve import NodeSurface, SnapshotEntry, ToolEntry, resolve_node
from robovoice.manifest.ros2_model import ros2_problems
from robovoice.middleware.base import NodeInfo


@dataclass(frozen=True, slots=True)
class CheckReport:
    """The outcome of checking a folder of manifests."""

    root: str
    files: tuple[str, ...]
    """The manifest files found (valid or not)."""
    tools: tuple[str, ...]
    """The tool and snapshot names the valid declarations would expose."""
    errors: tuple[ManifestError, ...]
    notes: tuple[str, ...] = ()
    """Things worth knowing that are not errors (e.g. a node not running, so not checked live)."""

    @property
    def ok(self) -> bool:
        return not self.errors

    def lines(self) -> list[str]:
        """One line per error (``file: $.path: message (fix: ...)``), the notes, then a summary."""
        out = [format_error(e) for e in self.errors]
        out += [f"note: {n}" for n in self.notes]
        verdict = "OK" if self.ok else f"{len(self.errors)} error{'s' if len(self.errors) != 1 else ''}"
        out.append(f"{self.root}: {len(self.files)} manifest file(s), {len(self.tools)} tool(s): {verdict}")
        return out


def check_manifest_dir(root: str | Path, nodes: Mapping[str, NodeInfo] | None = None) -> CheckReport:
    """Check every manifest under `root` (see `load_manifest_dir` for the layout)."""
    loaded = load_manifest_dir(root)
    files = sorted({*(m.source for m in loaded.manifests.values()), *(e.source for e in loaded.errors)})
    errors: list[ManifestError] = list(loaded.errors)
    notes: list[str] = []
    catalog = ToolCatalog()
    for node in sorted(loaded.manifests):
        item = loaded.manifests[node]
        if nodes is None:
            surface = _unchecked_surface(node, item.manifest, item.source)
        elif node in nodes:
            surface = resolve_node(nodes[node], item.manifest, item.source)
        else:
            notes.append(f"node {node!r} is not running: its RPCs and topics were not checked "
                         f"({item.source})")
            surface = _unchecked_surface(node, item.manifest, item.source)
        catalog.update(node, surface)
        errors.extend(ros2_problems(item.manifest, item.source))  # types and fields of `ros2` blocks
    errors.extend(catalog.errors())
    if not files:
        notes.append(f"no manifests found: expected <node>/mcp.json or <node>.mcp.json under {root}")
    tools = tuple(e.name for e in catalog.tools())
    if files:
        notes.extend(voice_role_notes(catalog))
    return CheckReport(str(root), tuple(files), tools, tuple(sort_errors(errors)), tuple(notes))


NO_STOP_TOOL = (
    "no tool declares the voice role \"stop\": a spoken \"stop\" cannot reach this robot without the "
    "language model; add \"voice\": {\"role\": \"stop\"} to its stop tool (docs/manifest.md)"
)


def voice_role_notes(catalog: ToolCatalog) -> list[str]:
    """What the voice pipeline will miss in these tools' voice roles (docs/manifest.md)."""
    roles = [e.voice.role for e in catalog.tools() if e.voice is not None]
    notes = [] if "stop" in roles else [NO_STOP_TOOL]
    if roles.count("stop") > 1:
        notes.append("more than one tool declares the voice role \"stop\": a spoken stop calls the first "
                     "by name")
    unchecked = sorted(e.name for e in catalog.tools() if not e.annotations.readOnlyHint
                       and (e.voice is None or not e.voice.words))
    if unchecked:
        notes.append(f"{UNCHECKED_FIT} {', '.join(unchecked)}")
    return notes


UNCHECKED_FIT = (
    "these actuation tools declare no \"voice\": {\"words\": [...]}, so a call the model makes of one is not "
    "checked against the words of the request (docs/judgement.md):"
)


def _unchecked_surface(node: str, manifest: Manifest, source: str) -> NodeSurface:
    """A surface built without a live node (RPC kinds unknown): for name checks only."""
    tools = tuple(
        ToolEntry(t.name, node, t.rpc, "rpc", t.description, dict(t.parameters), dict(t.defaults),
                  t.annotations, t.timeout_s or 0.0, source, f"$.tools[{i}]", t.voice)
        for i, t in enumerate(manifest.tools)
    )
    snaps = tuple(
        SnapshotEntry(s.name, node, s.topic, s.description, s.max_age_s, source, f"$.snapshots[{i}]", s.voice)
        for i, s in enumerate(manifest.snapshots)
    )
    return NodeSurface(node, source, tools, snaps)
