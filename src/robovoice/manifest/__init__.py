"""Manifests (`mcp.json`, one per node): models, loading with precise errors, resolution
against live nodes, and the tool catalog of the nodes present. See docs/manifest.md."""

from __future__ import annotations

from robovoice.errors import ManifestError
from robovoice.manifest.catalog import ToolCatalog
from robovoice.manifest.check import CheckReport, check_manifest_dir
from robovoice.manifest.errors import ManifestErrors, format_error
from robovoice.manifest.loader import (
    LoadedManifest,
    ManifestSet,
    load_manifest_dir,
    load_manifest_file,
    parse_manifest,
    validate_manifest,
)
from robovoice.manifest.model import Manifest, SnapshotDecl, ToolAnnotations, ToolDecl
from robovoice.manifest.resolve import (
    DEFAULT_TIMEOUT_S,
    CatalogEntry,
    NodeSurface,
    SnapshotEntry,
    ToolEntry,
    manifest_for,
    resolve_node,
    surface_for,
)

__all__ = [
    "DEFAULT_TIMEOUT_S",
    "CatalogEntry",
    "CheckReport",
    "LoadedManifest",
    "Manifest",
    "ManifestError",
    "ManifestErrors",
    "ManifestSet",
    "NodeSurface",
    "SnapshotDecl",
    "SnapshotEntry",
    "ToolAnnotations",
    "ToolCatalog",
    "ToolDecl",
    "ToolEntry",
    "check_manifest_dir",
    "format_error",
    "load_manifest_dir",
    "load_manifest_file",
    "manifest_for",
    "parse_manifest",
    "resolve_node",
    "surface_for",
    "validate_manifest",
]
