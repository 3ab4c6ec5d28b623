"""Read manifests: one text, one file, or a folder of them, with every error reported.

Folder layout (`load_manifest_dir`), one manifest per node, either form:

    DIR/<node>/mcp.json       e.g. manifests/navigation/mcp.json
    DIR/<node>.mcp.json       e.g. manifests/navigation.mcp.json

The file name names the node: the manifest's ``node`` must match it. Other files are
ignored. A bad file never hides the good ones: they load, and its errors are collected.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from robovoice.errors import ManifestError
from robovoice.json_limits import json_depth_exceeds
from robovoice.manifest.errors import ManifestErrors, json_path, sort_errors
from robovoice.manifest.model import Manifest
from robovoice.manifest.rules import semantic_errors
from robovoice.manifest.validation import translate

MANIFEST_FILE = "mcp.json"
MANIFEST_SUFFIX = ".mcp.json"
MAX_MANIFEST_DEPTH = 64


@dataclass(frozen=True, slots=True)
class LoadedManifest:
    """A valid manifest and where it came from (a file path, or a node's announcement)."""

    manifest: Manifest
    source: str


@dataclass(frozen=True, slots=True)
class ManifestSet:
    """The manifests of a folder: the good ones by node name, and the errors of the bad ones.

    `failed` maps the node name of each bad file (from its file name) to its errors, so
    that a broken override is reported instead of silently falling back.
    """

    root: str
    manifests: Mapping[str, LoadedManifest] = field(default_factory=dict)
    failed: Mapping[str, tuple[ManifestError, ...]] = field(default_factory=dict)
    errors: tuple[ManifestError, ...] = ()

    @property
    def ok(self) -> bool:
        return not self.errors

    def get(self, node: str) -> LoadedManifest | None:
        return self.manifests.get(node)

    def __contains__(self, node: object) -> bool:
        return node in self.manifests or node in self.failed


# --- one text / one value ------------------------------------------------------------


def parse_manifest(text: str, source: str) -> Manifest:
    """Parse and validate the text of an ``mcp.json``. Raises `ManifestErrors` with every problem."""
    data = _parse_json(text, source)
    return validate_manifest(data, source)


def validate_manifest(data: object, source: str) -> Manifest:
    """Validate an already parsed manifest (e.g. `NodeInfo.manifest`). Raises `ManifestErrors`."""
    if isinstance(data, Manifest):
        return data
    try:
        text = json.dumps(data, allow_nan=False, default=_mapping_as_dict)
        if json_depth_exceeds(text.encode("utf-8", "surrogatepass"), MAX_MANIFEST_DEPTH):
            raise ValueError(f"it nests deeper than {MAX_MANIFEST_DEPTH} levels")
    except (TypeError, ValueError, RecursionError) as exc:
        raise ManifestErrors([ManifestError(
            source, "$", f"the manifest is not plain JSON: {exc}",
            "use only objects, arrays, strings, finite numbers, true/false and null",
        )]) from None
    errors: list[ManifestError] = []
    manifest: Manifest | None = None
    try:
        manifest = Manifest.model_validate_json(text, strict=True)
    except ValidationError as exc:
        errors.extend(translate(exc, source))
    errors.extend(semantic_errors(data, source))
    if errors or manifest is None:
        raise ManifestErrors(errors)
    return manifest


def _mapping_as_dict(value: object) -> object:
    if isinstance(value, Mapping):
        return dict(value)
    raise TypeError(f"{type(value).__name__} is not a JSON value")


class _Pairs(dict[str, Any]):
    """A JSON object that remembers keys given twice (json drops all but the last)."""

    duplicates: list[str]


def _pairs(items: list[tuple[str, Any]]) -> _Pairs:
    obj = _Pairs()
    obj.duplicates = []
    for key, value in items:
        if key in obj:
            obj.duplicates.append(key)
        obj[key] = value
    return obj


def _no_constant(name: str) -> float:
    raise ValueError(f"{name} is not valid JSON")


def _parse_json(text: str, source: str) -> object:
    if json_depth_exceeds(text.encode("utf-8", "surrogatepass"), MAX_MANIFEST_DEPTH):
        raise ManifestErrors([ManifestError(
            source, "$", f"the manifest nests arrays/objects deeper than {MAX_MANIFEST_DEPTH} levels",
            "flatten it: no manifest needs that depth",
        )])
    try:
        data = json.loads(text, object_pairs_hook=_pairs, parse_constant=_no_constant)
    except json.JSONDecodeError as exc:
        raise ManifestErrors([ManifestError(
            source, "$", f"malformed JSON at line {exc.lineno}, column {exc.colno}: {exc.msg}",
            "correct the JSON syntax there (a missing comma or quote, a trailing comma, a comment)",
        )]) from None
    except ValueError as exc:
        raise ManifestErrors([ManifestError(
            source, "$", f"malformed JSON: {exc}", "use only finite numbers (no NaN or Infinity)",
        )]) from None
    duplicates = _duplicate_keys(data, (), source)
    if duplicates:
        raise ManifestErrors(duplicates)
    return data


def _duplicate_keys(value: object, loc: tuple[str | int, ...], source: str) -> list[ManifestError]:
    found: list[ManifestError] = []
    if isinstance(value, _Pairs):
        found.extend(
            ManifestError(source, json_path((*loc, k)), f"the key {k!r} appears more than once",
                          "keep only one of them (JSON keeps the last silently)")
            for k in dict.fromkeys(value.duplicates)
        )
        for key, item in value.items():
            found.extend(_duplicate_keys(item, (*loc, key), source))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            found.extend(_duplicate_keys(item, (*loc, index), source))
    return found


# --- files and folders ----------------------------------------------------------------


def load_manifest_file(path: str | Path) -> Manifest:
    """Read and validate one manifest file. Raises `ManifestErrors` naming the file."""
    source = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8-sig")  # tolerate a BOM
    except (OSError, UnicodeDecodeError) as exc:
        raise ManifestErrors([ManifestError(
            source, "$", f"cannot read the manifest: {exc}", "check that the file exists and is UTF-8 text",
        )]) from None
    return parse_manifest(text, source)


def manifest_files(root: str | Path) -> list[tuple[str, Path]]:
    """``(node name, path)`` of every manifest in the folder layout, by node name;
    for one node, ``<node>/mcp.json`` comes before ``<node>.mcp.json``."""
    base = Path(root)
    folders = sorted((p.parent.name, p) for p in base.glob(f"*/{MANIFEST_FILE}") if p.is_file())
    files = sorted(
        (p.name[: -len(MANIFEST_SUFFIX)], p) for p in base.glob(f"*{MANIFEST_SUFFIX}") if p.is_file()
    )
    return sorted(folders + files, key=lambda item: item[0])  # stable: folder form first


def load_manifest_dir(root: str | Path) -> ManifestSet:
    """Load every manifest of a folder (layout in the module docstring); never raises for a bad file."""
    base = Path(root)
    if not base.is_dir():
        error = ManifestError(
            str(base), "$", "not a folder of manifests",
            f"give a folder holding <node>/{MANIFEST_FILE} or <node>{MANIFEST_SUFFIX} files",
        )
        return ManifestSet(str(base), errors=(error,))
    good: dict[str, LoadedManifest] = {}
    failed: dict[str, list[ManifestError]] = {}
    for node, path in manifest_files(base):
        source = str(path)
        problems: list[ManifestError] = []
        try:
            manifest = load_manifest_file(path)
        except ManifestErrors as exc:
            problems = list(exc.errors)
        else:
            problems = _placement_errors(node, manifest, source, good)
            if not problems:
                good[node] = LoadedManifest(manifest, source)
        if problems:
            failed.setdefault(node, []).extend(problems)
    errors = sort_errors(e for group in failed.values() for e in group)
    return ManifestSet(str(base), good, {node: tuple(errs) for node, errs in failed.items()}, tuple(errors))


def _placement_errors(
    node: str, manifest: Manifest, source: str, good: Mapping[str, LoadedManifest]
) -> list[ManifestError]:
    if manifest.node != node:
        return [ManifestError(
            source, "$.node",
            f"the manifest is for node {manifest.node!r} but its file is named for node {node!r}",
            f"set \"node\": {node!r}, or move the file to {manifest.node}/{MANIFEST_FILE}",
        )]
    if node in good:
        return [ManifestError(
            source, "$.node", f"a second manifest for node {node!r} (the first is {good[node].source})",
            "keep one manifest per node: merge the two files",
        )]
    return []


def check_manifest_text(text: str, source: str) -> list[ManifestError]:
    """Every problem of a manifest text as a list (empty when it is valid)."""
    try:
        parse_manifest(text, source)
    except ManifestErrors as exc:
        return list(exc.errors)
    return []

