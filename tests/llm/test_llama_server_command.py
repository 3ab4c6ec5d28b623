"""The real servers' command lines (`llm.llama_server`), without starting one: the C++ server's
binary is found where scripts/build_llama_server.sh caches it, and a missing one says how to build it."""

from __future__ import annotations

from pathlib import Path

import pytest

from robovoice.errors import ConfigError
from robovoice.llm.llama_server import MODEL_ALIAS, llama_server_binary, server_command


def test_the_binary_is_cached_beside_the_model_unless_named() -> None:
    assert llama_server_binary({"ROBOVOICE_CACHE_DIR": "/c"}) == Path("/c/llama-server-11434.0.0/llama-server")
    assert llama_server_binary({"ROBOVOICE_LLAMA_SERVER": "/opt/ls", "ROBOVOICE_CACHE_DIR": "/c"}) == Path("/opt/ls")


def test_llama_server_runs_the_models_template_on_one_slot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    binary = tmp_path / "llama-server"
    binary.write_text("")
    monkeypatch.setenv("ROBOVOICE_LLAMA_SERVER", str(binary))
    command = server_command("llama-server", Path("/m.gguf"))
    assert command[0] == str(binary) and "--jinja" in command
    assert command[command.index("--alias") + 1] == MODEL_ALIAS and command[command.index("--parallel") + 1] == "1"
    assert command[command.index("--port") + 1] == "0"  # the OS chooses; the log says which


def test_a_missing_llama_server_names_the_build_script(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROBOVOICE_LLAMA_SERVER", str(tmp_path / "absent"))
    with pytest.raises(ConfigError, match=r"scripts/build_llama_server\.sh"):
        server_command("llama-server", Path("/m.gguf"))
    with pytest.raises(ConfigError, match="choose one of chatml-function-calling, gguf-template, llama-server"):
        server_command("vllm", Path("/m.gguf"))
