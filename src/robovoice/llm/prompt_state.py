"""The embedded model's evaluated prefix (system prompt + tools), kept on disk between runs.

Evaluating the unchanging prefix is most of a cold start: 1,246 tokens took 40-80 s on a
2-core machine (docs/performance.md), and every start of the assistant, the voice pipeline or
a soak paid it again. After a warm-up the model's state for the prefix is written with
llama.cpp's own session file (``llama_state_save_file``: the key/value cache and the
tokens, about 36 MB for the sim robot's prefix), and the next warm-up for the same prefix
loads it in well under a second instead.

A state is only used for exactly what made it: the file's name is a hash of llama-cpp-python's
version, the model file (path, size, modification time), the context size, the CPU's feature
flags (the wheel is built for this CPU) and the prefix's tokens; the tokens read back must
equal the prefix's too. Anything else, or a file that does not load, and the prefix is
evaluated as before. The newest `KEEP` states are kept under ``<cache>/prompt-states/``.
"""

from __future__ import annotations

import contextlib
import ctypes
import hashlib
import json
import logging
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

log = logging.getLogger(__name__)

#: How many states are kept (the newest): one per robot and prompt in use, about 36 MB each.
KEEP = 4
FOLDER = "prompt-states"


def _cpu_flags() -> str:
    with contextlib.suppress(OSError), open("/proc/cpuinfo", encoding="utf-8") as f:
        for line in f:
            if line.startswith("flags"):
                return line.strip()
    return ""


def state_path(cache_dir: Path, llama_cpp: Any, model_path: Path, n_ctx: int, tokens: Sequence[int]) -> Path:
    """Where the state of `tokens` evaluated by this model, library and CPU is kept."""
    stat = model_path.stat()
    key = json.dumps([llama_cpp.__version__, str(model_path.resolve()), stat.st_size, stat.st_mtime_ns, n_ctx,
                      hashlib.sha256(_cpu_flags().encode()).hexdigest(), list(tokens)])
    return cache_dir / FOLDER / f"{hashlib.sha256(key.encode()).hexdigest()[:32]}.state"


def load(llama: Any, llama_cpp: Any, path: Path, tokens: Sequence[int]) -> bool:
    """Restore the state saved at `path` into `llama`; whether it now holds `tokens` evaluated."""
    if not path.is_file():
        return False
    capacity = llama.n_ctx()
    read = (llama_cpp.llama_token * capacity)()
    count = ctypes.c_size_t(0)
    ok = llama_cpp.llama_state_load_file(llama._ctx.ctx, str(path).encode(), read, capacity, ctypes.byref(count))
    if not ok or list(read[: count.value]) != list(tokens):
        log.warning("the saved prompt state %s does not load or is for other words; evaluating the prefix", path)
        llama.reset()  # the next evaluation clears the cache from token 0
        return False
    llama.input_ids[: count.value] = list(tokens)
    llama.n_tokens = count.value
    with contextlib.suppress(OSError):
        os.utime(path)  # the newest is kept longest
    return True


def save(llama: Any, llama_cpp: Any, path: Path, tokens: Sequence[int]) -> None:
    """Write `llama`'s state (holding `tokens` evaluated) to `path`, and drop the oldest beyond
    `KEEP`. A state that cannot be written only costs the next start its warm-up."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        partial = path.with_suffix(f".{os.getpid()}.partial")
        ids = (llama_cpp.llama_token * len(tokens))(*tokens)
        if not llama_cpp.llama_state_save_file(llama._ctx.ctx, str(partial).encode(), ids, len(tokens)):
            partial.unlink(missing_ok=True)
            log.warning("could not save the prompt state to %s", path)
            return
        os.replace(partial, path)  # whole or not at all, for another process loading it
        states = sorted(path.parent.glob("*.state"), key=lambda p: p.stat().st_mtime_ns, reverse=True)
        for old in states[KEEP:]:
            old.unlink(missing_ok=True)
    except OSError as exc:
        log.warning("could not save the prompt state to %s: %s", path, exc)


def warm(llama: Any, llama_cpp: Any, folder: Path | None, n_ctx: int, tokens: Sequence[int],
         evaluate: Callable[[], object]) -> bool:
    """Bring `llama` to `tokens` evaluated: from the state kept under `folder` (None: none is
    kept), else by `evaluate`, whose result is then kept; whether it came from disk."""
    path = state_path(folder, llama_cpp, Path(llama.model_path), n_ctx, tokens) if folder is not None else None
    if path is not None and load(llama, llama_cpp, path, tokens):
        return True
    evaluate()
    if path is not None:
        save(llama, llama_cpp, path, tokens)
    return False
