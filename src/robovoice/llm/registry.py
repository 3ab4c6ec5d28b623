"""Backends from spec strings: ``local``, ``local:/path/model.gguf``, ``http(s)://host/v1#model``.

    chain_from_specs(["http://edge:8000/v1#Qwen/Qwen3-Omni-30B-A3B-Instruct", "local"])

An HTTP spec names its model after ``#`` or through `BackendSpec.model`. API
keys are never part of a spec: they come from `BackendSpec.api_key`, which
config code fills with `api_key_from` (an environment variable name or a file).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from robovoice.config import read_secret_file
from robovoice.errors import ConfigError
from robovoice.llm.base import LOCAL_DEADLINES, Deadlines, LLMBackend
from robovoice.llm.failover import Backoff, FailoverBackend
from robovoice.llm.local import LocalLlamaBackend
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.urls import check_http_url

ACCEPTED_FORMS = (
    "'local' (the embedded Qwen2.5-Coder-1.5B model)",
    "'local:/path/to/model.gguf' (any GGUF file)",
    "'http://host:port/v1#model-name' or 'https://…/v1#model-name' (an OpenAI-compatible server)",
)


@dataclass(frozen=True, slots=True)
class BackendSpec:
    """One backend of a chain, with the options a bare spec string cannot carry."""

    spec: str
    model: str | None = None
    name: str | None = None
    api_key: str | None = None
    accepts_audio: bool = False
    deadlines: Deadlines | None = None
    extra_body: Mapping[str, Any] = field(default_factory=dict)
    n_threads: int = 2
    cache_dir: Path | None = None


def api_key_from(environ: Mapping[str, str], *, env_var: str | None = None, key_file: Path | None = None) -> str | None:
    """The API key named by config: from ``environ[env_var]`` or the first line of ``key_file``.

    ``None`` when neither is configured (a local server without keys); a named
    but missing variable or file is a `ConfigError`.
    """
    if env_var and key_file:
        raise ConfigError("give the API key as an environment variable name or a file, not both")
    if env_var:
        value = environ.get(env_var, "").strip()
        if not value:
            raise ConfigError(f"environment variable {env_var} (the LLM API key) is not set")
        return value
    if key_file:
        return read_secret_file(key_file, "LLM API key")
    return None


def _unknown(spec: str) -> ConfigError:
    return ConfigError(f"unknown LLM backend {spec!r}; accepted forms: {'; '.join(ACCEPTED_FORMS)}")


def backend_from_spec(spec: str | BackendSpec) -> LLMBackend:
    """One backend. Cheap: nothing is loaded or connected until the first turn."""
    options = spec if isinstance(spec, BackendSpec) else BackendSpec(spec)
    text = options.spec.strip()
    if text == "local" or text.startswith("local:"):
        path = text[len("local:") :].strip() if text.startswith("local:") else ""
        if text.startswith("local:") and not path:
            raise _unknown(text)
        return LocalLlamaBackend(
            model_path=Path(path).expanduser() if path else None,
            name=options.name or "local",
            n_threads=options.n_threads,
            deadlines=options.deadlines or LOCAL_DEADLINES,
            cache_dir=options.cache_dir,
        )
    parts = urlsplit(text)
    if parts.scheme in ("http", "https") and parts.netloc:
        check_http_url(text, "LLM backend", example="http://edge-server:8000/v1#model-name",
                       secret_fix="give the API key with --api-key-env / --api-key-file (or api_key_env / "
                                  "api_key_file in the config)")
        if parts.query:
            raise ConfigError(f"LLM backend {text!r}: unexpected query '?{parts.query}'; write the server's base "
                              f"URL, e.g. http://edge-server:8000/v1#model-name")
        if options.model and parts.fragment and options.model != parts.fragment:
            raise ConfigError(f"LLM backend {text!r} names model {parts.fragment!r} and --model {options.model!r}; "
                              f"give one")
        model = options.model or parts.fragment
        if not model:
            hint = f"write it after '#', e.g. {text}#my-model"
            raise ConfigError(f"LLM backend {text!r} needs a model name: {hint}")
        base_url = text.split("#", 1)[0].rstrip("/")
        return OpenAICompatBackend(
            base_url,
            model,
            name=options.name or parts.netloc,
            api_key=options.api_key,
            accepts_audio=options.accepts_audio,
            deadlines=options.deadlines,
            extra_body=options.extra_body,
        )
    raise _unknown(text)


def chain_from_specs(
    specs: Sequence[str | BackendSpec],
    *,
    backoff: Backoff | None = None,
    clock: Callable[[], float] = time.monotonic,
) -> FailoverBackend:
    """A failover chain, tried in the given order (even a single backend, for uniform health)."""
    if not specs:
        raise ConfigError(f"no LLM backend configured; accepted forms: {'; '.join(ACCEPTED_FORMS)}")
    return FailoverBackend([backend_from_spec(s) for s in specs], backoff=backoff, clock=clock)
