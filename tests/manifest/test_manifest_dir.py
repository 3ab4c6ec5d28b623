"""`load_manifest_file` / `load_manifest_dir`: the folder layout, and one bad file never hides the others."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from robovoice.manifest import ManifestErrors, load_manifest_dir, load_manifest_file


def write(path: Path, data: Any) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(data if isinstance(data, str) else json.dumps(data, indent=2), encoding="utf-8")
    return path


def small(node: str, tool: str = "") -> dict[str, Any]:
    return {"node": node, "tools": [{"name": tool or f"{node}_do", "rpc": "do", "description": "does it"}]}


def test_load_file(tmp_path: Path, nav: dict[str, Any]) -> None:
    path = write(tmp_path / "navigation" / "mcp.json", nav)
    assert load_manifest_file(path).node == "navigation"


def test_load_file_errors_name_the_file(tmp_path: Path) -> None:
    path = write(tmp_path / "navigation" / "mcp.json", '{"node": "navigation",')
    with pytest.raises(ManifestErrors) as caught:
        load_manifest_file(path)
    assert caught.value.source == str(path)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ManifestErrors, match="cannot read the manifest"):
        load_manifest_file(tmp_path / "nope.json")


def test_not_utf8(tmp_path: Path) -> None:
    path = tmp_path / "x.mcp.json"
    path.write_bytes(b'{"node": "\xff"}')
    with pytest.raises(ManifestErrors, match="UTF-8"):
        load_manifest_file(path)


def test_both_layouts(tmp_path: Path, nav: dict[str, Any]) -> None:
    write(tmp_path / "navigation" / "mcp.json", nav)
    write(tmp_path / "projector.mcp.json", small("projector"))
    write(tmp_path / "README.md", "not a manifest")
    write(tmp_path / "other" / "config.json", {"not": "a manifest"})
    loaded = load_manifest_dir(tmp_path)
    assert loaded.ok
    assert sorted(loaded.manifests) == ["navigation", "projector"]
    assert loaded.manifests["projector"].source == str(tmp_path / "projector.mcp.json")


def test_one_bad_file_among_good_ones(tmp_path: Path, nav: dict[str, Any]) -> None:
    write(tmp_path / "navigation" / "mcp.json", nav)
    bad = write(tmp_path / "projector" / "mcp.json", '{"node": "projector", "tools": [}')
    worse = small("communication")
    worse["tools"][0]["name"] = "start video call"
    worse["tool"] = []
    write(tmp_path / "communication.mcp.json", worse)
    write(tmp_path / "base.mcp.json", small("base"))
    loaded = load_manifest_dir(tmp_path)
    assert not loaded.ok
    assert sorted(loaded.manifests) == ["base", "navigation"]
    assert sorted(loaded.failed) == ["communication", "projector"]
    assert [e.source for e in loaded.failed["projector"]] == [str(bad)]
    assert [e.path for e in loaded.failed["communication"]] == ["$.tool", "$.tools[0].name"]
    assert len(loaded.errors) == 3
    assert "projector" in loaded and "navigation" in loaded and "nobody" not in loaded


def test_node_must_match_the_file_name(tmp_path: Path) -> None:
    path = write(tmp_path / "navigation" / "mcp.json", small("nav"))
    loaded = load_manifest_dir(tmp_path)
    [error] = loaded.errors
    assert (error.source, error.path) == (str(path), "$.node")
    assert "'nav'" in error.message and "'navigation'" in error.message
    assert "navigation" in loaded.failed


def test_two_manifests_for_one_node(tmp_path: Path) -> None:
    write(tmp_path / "base" / "mcp.json", small("base"))
    second = write(tmp_path / "base.mcp.json", small("base", "other"))
    loaded = load_manifest_dir(tmp_path)
    assert loaded.manifests["base"].source == str(tmp_path / "base" / "mcp.json")
    [error] = loaded.errors
    assert error.source == str(second)
    assert "a second manifest for node 'base'" in error.message


def test_not_a_folder(tmp_path: Path) -> None:
    loaded = load_manifest_dir(tmp_path / "missing")
    assert not loaded.ok
    assert "not a folder" in loaded.errors[0].message


def test_byte_order_mark_is_tolerated(tmp_path: Path, nav: dict[str, Any]) -> None:
    path = tmp_path / "navigation.mcp.json"
    path.write_bytes(b"\xef\xbb\xbf" + json.dumps(nav).encode())
    assert load_manifest_file(path).node == "navigation"
