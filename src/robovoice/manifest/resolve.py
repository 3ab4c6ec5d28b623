"""Resolve a manifest against a live node: the node's *surface* of tools and snapshots.

`resolve_node` checks every declaration against what the node announced (its RPCs with
their kinds and parameter names, its topics) and turns the good ones into `ToolEntry` /
`SnapshotEntry`; a bad declaration is left out with a `ManifestError`, the rest stay.

Defaults: a `defaults` key that is *not* in ``parameters.properties`` is a fixed argument
(hidden from the model, always sent, the model cannot override it); a key that *is* in
``properties`` is a default the model may override (it shows in the input schema as the
property's ``"default"`` and is no longer required). ``additionalProperties`` defaults to
false: the model may pass only the declared properties.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from robovoice.errors import ManifestError
from robovoice.manifest.errors import ManifestErrors, did_you_mean, json_path, sort_errors
from robovoice.manifest.loader import LoadedManifest, ManifestSet, validate_manifest
from robovoice.manifest.model import EMPTY_OBJECT_SCHEMA, Manifest, SnapshotDecl, ToolAnnotations, ToolDecl
from robovoice.manifest.voice import VoiceDecl
from robovoice.middleware.base import JSON, NodeInfo, RpcInfo, RpcKind

DEFAULT_TIMEOUT_S: Mapping[RpcKind, float] = {"rpc": 10.0, "action": 300.0}

SNAPSHOT_ANNOTATIONS = ToolAnnotations(
    readOnlyHint=True, destructiveHint=False, idempotentHint=True, openWorldHint=False
)


@dataclass(frozen=True, slots=True)
class ToolEntry:
    """An MCP tool that calls one RPC or action of one node.

    `input_schema` and `defaults` are shared: treat them as read-only. Hashable (the two
    dicts are left out of the hash)."""

    name: str
    node: str
    rpc: str
    kind: RpcKind
    description: str
    input_schema: dict[str, Any] = field(hash=False)
    defaults: dict[str, JSON] = field(hash=False)
    annotations: ToolAnnotations
    timeout_s: float
    source: str
    path: str = ""
    """JSON path of the declaration in `source` (``$.tools[1]``), for error messages."""
    voice: VoiceDecl | None = None
    """The declaration's voice section (role, phrases), carried to clients in ``_meta``."""
    for_model: bool = True
    """False: left out of the model's tool list (``_meta``, `model.FOR_MODEL_META_KEY`)."""

    @property
    def fixed(self) -> dict[str, JSON]:
        """The defaults hidden from the model (not in the input schema's properties)."""
        props = self.input_schema.get("properties", {})
        return {k: v for k, v in self.defaults.items() if k not in props}

    def call_arguments(self, arguments: Mapping[str, JSON]) -> dict[str, JSON]:
        """The RPC's arguments for the model's (already validated) `arguments`:
        overridable defaults, then the model's values, then the fixed arguments."""
        props = self.input_schema.get("properties", {})
        merged: dict[str, JSON] = {k: v for k, v in self.defaults.items() if k in props}
        merged.update(arguments)
        merged.update(self.fixed)
        return merged


@dataclass(frozen=True, slots=True)
class SnapshotEntry:
    """A read-only MCP tool returning the latest message of one topic."""

    name: str
    node: str
    topic: str
    description: str
    max_age_s: float
    source: str
    path: str = ""
    voice: VoiceDecl | None = None
    for_model: bool = True

    @property
    def input_schema(self) -> dict[str, Any]:
        return copy.deepcopy(EMPTY_OBJECT_SCHEMA)

    @property
    def annotations(self) -> ToolAnnotations:
        return SNAPSHOT_ANNOTATIONS


CatalogEntry = ToolEntry | SnapshotEntry


@dataclass(frozen=True, slots=True)
class NodeSurface:
    """What one node exposes: its valid tools and snapshots, and the errors of the rest."""

    node: str
    source: str = ""
    tools: tuple[ToolEntry, ...] = ()
    snapshots: tuple[SnapshotEntry, ...] = ()
    errors: tuple[ManifestError, ...] = field(default=())

    @property
    def entries(self) -> tuple[CatalogEntry, ...]:
        return (*self.tools, *self.snapshots)

    def raise_for_errors(self) -> None:
        if self.errors:
            raise ManifestErrors(self.errors)


def resolve_node(info: NodeInfo, manifest: Manifest, source: str) -> NodeSurface:
    """Check `manifest` against the live node `info`; keep the good declarations."""
    if manifest.node != info.name:
        error = ManifestError(
            source, "$.node", f"the manifest is for node {manifest.node!r}, not for {info.name!r}",
            f"set \"node\": {info.name!r}, or give this manifest to the node {manifest.node!r}",
        )
        return NodeSurface(info.name, source, errors=(error,))
    tools: list[ToolEntry] = []
    snapshots: list[SnapshotEntry] = []
    errors: list[ManifestError] = []
    for index, decl in enumerate(manifest.tools):
        loc = ("tools", index)
        problems = _tool_problems(info, decl, loc, source)
        if problems:
            errors.extend(problems)
            continue
        rpc = info.rpc(decl.rpc)
        assert rpc is not None  # checked by _tool_problems
        tools.append(_tool_entry(info.name, rpc, decl, source, json_path(loc)))
    for index, snap in enumerate(manifest.snapshots):
        loc = ("snapshots", index)
        problem = _snapshot_problem(info, snap, loc, source)
        if problem is not None:
            errors.append(problem)
            continue
        snapshots.append(SnapshotEntry(
            snap.name, info.name, snap.topic, snap.description, snap.max_age_s, source, json_path(loc), snap.voice,
            snap.for_model,
        ))
    return NodeSurface(info.name, source, tuple(tools), tuple(snapshots), tuple(sort_errors(errors)))


def _tool_problems(info: NodeInfo, decl: ToolDecl, loc: tuple[str, int], source: str) -> list[ManifestError]:
    rpc = info.rpc(decl.rpc)
    if rpc is None:
        offered = [r.name for r in info.rpcs]
        return [ManifestError(
            source, json_path((*loc, "rpc")), f"node {info.name!r} offers no RPC or action {decl.rpc!r}",
            did_you_mean(decl.rpc, offered, what=f"RPCs and actions of {info.name!r}"),
        )]
    problems: list[ManifestError] = []
    takes = ", ".join(repr(p) for p in rpc.params) or "no arguments"
    for prop in decl.parameters.get("properties", {}):
        if prop not in rpc.params:
            problems.append(ManifestError(
                source, json_path((*loc, "parameters", "properties", prop)),
                f"{rpc.kind} {rpc.name!r} of node {info.name!r} takes no parameter {prop!r}",
                f"{did_you_mean(prop, rpc.params, what='parameters')}; it takes {takes}",
            ))
    for key in decl.defaults:
        if key not in rpc.params:
            problems.append(ManifestError(
                source, json_path((*loc, "defaults", key)),
                f"default for {key!r}, but {rpc.kind} {rpc.name!r} of node {info.name!r} "
                "takes no such parameter",
                f"{did_you_mean(key, rpc.params, what='parameters')}; it takes {takes}",
            ))
    return problems


def _snapshot_problem(
    info: NodeInfo, snap: SnapshotDecl, loc: tuple[str, int], source: str
) -> ManifestError | None:
    if snap.topic in info.topics:
        return None
    return ManifestError(
        source, json_path((*loc, "topic")), f"node {info.name!r} publishes no topic {snap.topic!r}",
        did_you_mean(snap.topic, info.topics, what=f"topics of {info.name!r}"),
    )


def _tool_entry(node: str, rpc: RpcInfo, decl: ToolDecl, source: str, path: str) -> ToolEntry:
    return ToolEntry(
        name=decl.name,
        node=node,
        rpc=rpc.name,
        kind=rpc.kind,
        description=decl.description,
        input_schema=input_schema(decl.parameters, decl.defaults),
        defaults=copy.deepcopy(decl.defaults),
        annotations=decl.annotations,
        timeout_s=decl.timeout_s if decl.timeout_s is not None else DEFAULT_TIMEOUT_S[rpc.kind],
        source=source,
        path=path,
        voice=decl.voice,
        for_model=decl.for_model,
    )


def input_schema(parameters: Mapping[str, Any], defaults: Mapping[str, JSON]) -> dict[str, Any]:
    """The schema the model sees: `parameters` with the overridable defaults shown as
    ``"default"``, those properties no longer required, and ``additionalProperties: false``
    unless the manifest says otherwise."""
    schema = copy.deepcopy(dict(parameters))
    props: dict[str, Any] = schema.setdefault("properties", {})
    for key, value in defaults.items():
        prop = props.get(key)
        if isinstance(prop, dict):
            prop.setdefault("default", copy.deepcopy(value))
    if "required" in schema:
        schema["required"] = [r for r in schema["required"] if r not in defaults]
        if not schema["required"]:
            del schema["required"]
    schema.setdefault("additionalProperties", False)
    return schema


# --- where a node's manifest comes from ---------------------------------------------


def manifest_for(info: NodeInfo, override: ManifestSet | None = None) -> LoadedManifest | None:
    """The manifest that applies to `info`: the override folder's (by node name) if it
    has one, else the node's own announcement. None when neither exists: the node then
    exposes nothing (not a failure). Raises `ManifestErrors` when the applicable manifest
    is invalid, including a broken override file (no silent fallback to the announcement)."""
    if override is not None:
        broken = override.failed.get(info.name)
        if broken:
            raise ManifestErrors(broken)
        found = override.get(info.name)
        if found is not None:
            return found
    if info.manifest is None:
        return None
    source = info.manifest_source or f"<manifest announced by node {info.name!r}>"
    return LoadedManifest(validate_manifest(info.manifest, source), source)


def surface_for(info: NodeInfo, override: ManifestSet | None = None) -> NodeSurface:
    """`manifest_for` then `resolve_node`, with every error inside the returned surface.
    What the MCP server calls when a node joins."""
    try:
        loaded = manifest_for(info, override)
    except ManifestErrors as exc:
        return NodeSurface(info.name, exc.source, errors=exc.errors)
    if loaded is None:
        return NodeSurface(info.name)
    return resolve_node(info, loaded.manifest, loaded.source)
