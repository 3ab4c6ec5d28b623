"""Configuration: one TOML file, read once at the edge and passed down frozen.

Folders come from the environment through `environment()`; secrets from files through
`read_secret_file()` (an API key may also come from an environment variable the config names).

    # robovoice.toml
    [robot]
    robot = "sim"                        # the embedded simulated robot (default), or:
    # middleware = "zenoh://127.0.0.1:7447"; manifests = "path/to/manifests"
    # server = "http://robot.local:8765/mcp"; token_file = "~/.config/robovoice/robot.token"

    [[llm.backends]]                     # tried in order each turn (failover)
    url = "http://edge-server:8000/v1"   # any OpenAI-compatible server: vLLM, llama.cpp, Ollama, a cloud
    model = "Qwen/Qwen3-Omni-30B-A3B-Instruct"
    api_key_env = "EDGE_API_KEY"         # or api_key_file = "..."; never the key itself
    accepts_audio = true

    [[llm.backends]]
    local = true                         # the embedded model (or model_path = "other.gguf")
"""

from __future__ import annotations

import logging
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from robovoice.errors import ConfigError

log = logging.getLogger(__name__)


class _Frozen(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class RobotConfig(_Frozen):
    robot: str | None = None
    middleware: str | None = None
    manifests: Path | None = None
    server: str | None = None
    token_file: Path | None = None
    sim_speed: float = Field(default=1.0, gt=0)


class BackendConfig(_Frozen):
    url: str | None = None
    model: str | None = None
    local: bool = False
    model_path: Path | None = None
    api_key_env: str | None = None
    api_key_file: Path | None = None
    accepts_audio: bool = False
    connect_s: float | None = Field(default=None, gt=0)
    first_token_s: float | None = Field(default=None, gt=0)
    extra_body: dict[str, Any] = Field(default_factory=dict)

    @model_validator(mode="after")
    def _kind(self) -> BackendConfig:
        if self.local == bool(self.url):
            raise ValueError("each backend needs either `url` (an OpenAI-compatible server) or `local = true`")
        return self


class LLMConfig(_Frozen):
    backends: tuple[BackendConfig, ...] = ()


class VoiceConfig(_Frozen):
    wake_model: str = "hey_jarvis"
    # what the wake word says, for stripping it from transcripts and for speech-to-text hints;
    # default: the bundled model's name as words ("hey_mycroft" -> "hey mycroft")
    wake_phrase: str | None = None
    wake_threshold: float = Field(default=0.5, gt=0, lt=1)
    end_of_turn_silence_ms: int = Field(default=500, ge=100)
    max_utterance_s: float = Field(default=15.0, gt=0)
    follow_up_s: float = Field(default=6.0, ge=0)
    # speech-to-text: Whisper tiny.en (takes vocabulary hints), Moonshine base-en, or none
    # (only with an audio-capable model)
    stt: Literal["whisper", "moonshine", "none"] = "whisper"
    vocabulary: tuple[str, ...] = ()  # extra words for speech-to-text (names, places)


class Config(_Frozen):
    robot: RobotConfig = Field(default_factory=RobotConfig)
    llm: LLMConfig = Field(default_factory=LLMConfig)
    voice: VoiceConfig = Field(default_factory=VoiceConfig)


def load_config(path: Path | None) -> Config:
    """Read a TOML config file (None: all defaults). Errors name the file and the field."""
    if path is None:
        return Config()
    try:
        raw = tomllib.loads(path.expanduser().read_text(encoding="utf-8"))
    except OSError as exc:
        raise ConfigError(f"cannot read config file {path}: {exc.strerror}") from exc
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: not valid TOML: {exc}") from exc
    try:
        return Config.model_validate(raw)
    except ValidationError as exc:
        problems = "; ".join(f"{'.'.join(str(p) for p in e['loc'])}: {e['msg']}" for e in exc.errors())
        raise ConfigError(f"{path}: {problems}") from exc


def read_secret_file(path: Path, what: str) -> str:
    """The secret (a bearer token, an API key) held in `path`, whitespace stripped.
    Unreadable or empty → `ConfigError` naming `what` and the file; a file others can read
    is allowed but logged, since secrets belong in files only their owner reads."""
    path = path.expanduser()
    try:
        value = path.read_text(encoding="utf-8").strip()
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"cannot read the {what} file {path}: {exc}") from None
    if not value:
        raise ConfigError(f"the {what} file {path} is empty")
    if path.stat().st_mode & 0o077:
        log.warning("the %s file %s can be read by other users; chmod 600 it", what, path)
    return value


@dataclass(frozen=True, slots=True)
class Environment:
    """The folders robovoice keeps files in, from the environment, read once."""

    cache_dir: Path
    state_dir: Path


def environment(env: Mapping[str, str] | None = None) -> Environment:
    """``$ROBOVOICE_CACHE_DIR``, else ``$XDG_CACHE_HOME/robovoice``, else ``~/.cache/robovoice``;
    likewise ``$ROBOVOICE_STATE_DIR`` / ``$XDG_STATE_HOME`` / ``~/.local/state`` for the state."""
    env = os.environ if env is None else env
    home = Path(env.get("HOME", str(Path.home())))

    def folder(own: str, xdg: str, fallback: Path) -> Path:
        if env.get(own):
            return Path(env[own]).expanduser()
        return Path(env[xdg]).expanduser() / "robovoice" if env.get(xdg) else fallback / "robovoice"

    return Environment(folder("ROBOVOICE_CACHE_DIR", "XDG_CACHE_HOME", home / ".cache"),
                       folder("ROBOVOICE_STATE_DIR", "XDG_STATE_HOME", home / ".local" / "state"))
