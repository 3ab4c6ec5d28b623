"""Backends from spec strings, and API keys from config."""

from __future__ import annotations

from pathlib import Path

import pytest

from robovoice.errors import ConfigError
from robovoice.llm.failover import FailoverBackend
from robovoice.llm.local import LocalLlamaBackend
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.llm.registry import BackendSpec, api_key_from, backend_from_spec, chain_from_specs

needs_llama = pytest.mark.usefixtures("llama_installed")


async def test_http_spec_with_model_after_hash() -> None:
    backend = backend_from_spec("http://edge.local:8000/v1#Qwen/Qwen3-Omni-30B-A3B-Instruct")
    assert isinstance(backend, OpenAICompatBackend)
    assert backend.url == "http://edge.local:8000/v1/chat/completions"
    assert backend.model == "Qwen/Qwen3-Omni-30B-A3B-Instruct"
    assert backend.name == "edge.local:8000"
    await backend.aclose()


async def test_http_spec_options() -> None:
    spec = BackendSpec("https://api.example.com/v1/", model="gpt-x", name="cloud", api_key="k", accepts_audio=True)
    backend = backend_from_spec(spec)
    assert isinstance(backend, OpenAICompatBackend)
    assert (backend.base_url, backend.model, backend.name, backend.accepts_audio) == (
        "https://api.example.com/v1",
        "gpt-x",
        "cloud",
        True,
    )
    await backend.aclose()


@pytest.mark.parametrize("spec", ["foo", "ftp://host/v1#m", "local:", "", "http:///v1#m"])
def test_unknown_specs_list_the_accepted_forms(spec: str) -> None:
    with pytest.raises(ConfigError) as info:
        backend_from_spec(spec)
    assert "'local'" in str(info.value) and "local:/path/to/model.gguf" in str(info.value)
    assert "http://host:port/v1#model-name" in str(info.value)


def test_http_spec_without_model_says_how() -> None:
    with pytest.raises(ConfigError, match="#my-model"):
        backend_from_spec("http://edge:8000/v1")


@needs_llama
async def test_local_specs(tmp_path: Path) -> None:
    gguf = tmp_path / "m.gguf"
    backend = backend_from_spec(f"local:{gguf}")
    assert isinstance(backend, LocalLlamaBackend) and backend.model_path == gguf
    await backend.aclose()


@needs_llama
async def test_a_chain_keeps_its_order(tmp_path: Path) -> None:
    chain = chain_from_specs(
        ["http://edge:8000/v1#omni", BackendSpec("https://cloud/v1", model="m"), f"local:{tmp_path}/x.gguf"]
    )
    assert isinstance(chain, FailoverBackend)
    assert [b.name for b in chain.backends] == ["edge:8000", "cloud", "local"]
    await chain.aclose()


def test_an_empty_chain_is_a_config_error() -> None:
    with pytest.raises(ConfigError, match="no LLM backend"):
        chain_from_specs([])


def test_api_key_from_env_or_file(tmp_path: Path) -> None:
    key_file = tmp_path / "key"
    key_file.write_text("sk-from-file\n")
    assert api_key_from({"MY_KEY": "sk-env"}, env_var="MY_KEY") == "sk-env"
    assert api_key_from({}, key_file=key_file) == "sk-from-file"
    assert api_key_from({}) is None
    with pytest.raises(ConfigError, match="MY_KEY"):
        api_key_from({}, env_var="MY_KEY")
    with pytest.raises(ConfigError, match="cannot read"):
        api_key_from({}, key_file=tmp_path / "missing")
    with pytest.raises(ConfigError, match="not both"):
        api_key_from({"MY_KEY": "x"}, env_var="MY_KEY", key_file=key_file)
