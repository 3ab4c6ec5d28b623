"""Configuration: one TOML file, read once at the edge and passed down frozen.

Folders come from the environment through `environment()`; secrets from files through
`read_secret_file()` (an API key may also come from an environment variable the config names).

    # robovoice.toml
    [robot]
    address = "sim://?speed=2"           # the embedded simulated robot (default: sim://), or any
                                         # robot address (robovoice.address): a middleware URI
    # address = "zenoh://127.0.0.1:7447"; manifests = "path/to/manifests"
    # address = "http://robot.local:8765/mcp"; token_file = "~/.config/robovoice/robot.token"
    # address = "stdio:robovoice serve --robot sim"

    [[llm.backends]]                     # tried in order each turn (failover)
    url = "http://edge-server:8000/v1"   # any OpenAI-compatible server: vLLM, llama.cpp, Ollama, a cloud
    model = "Qwen/Qwen3-Omni-30B-A3B-Instruct"
    api_key_env = "EDGE_API_KEY"         # or api_key_file = "..."; never the key itself
    accepts_audio = true

    [[llm.backends]]
    local = true                         # the embedded model (or model_path = "other.gguf")
"""

from __future__ import annotations

import dataclasses
import logging
import os
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path, PurePath
from typing import TYPE_CHECKING, Any, Literal
from urllib.parse import urlsplit

from pydantic import BaseModel, ConfigDict, Field, ValidationError, ValidationInfo, field_validator, model_validator

from robovoice.address import HttpAddress, LocalAddress, RobotAddress, StdioAddress, parse_robot_address
from robovoice.errors import ConfigError
from robovoice.urls import check_http_url

if TYPE_CHECKING:
    from robovoice.llm.base import Deadlines

log = logging.getLogger(__name__)


class _Frozen(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


_OLD_ROBOT_KEYS = {"robot", "middleware", "server", "sim_speed"}


class RobotConfig(_Frozen):
    """Which robot (`address`, see `robovoice.address`) and what goes with it: `manifests`
    (a folder replacing the nodes' own; robots served in this process) and `token_file`
    (the bearer token of an http(s) MCP server). The one robot config: the TOML ``[robot]``
    section, and what the command-line options make of it."""

    address: str = "sim://"
    manifests: Path | None = None
    token_file: Path | None = None

    @model_validator(mode="before")
    @classmethod
    def _old_keys(cls, data: Any) -> Any:
        if isinstance(data, Mapping) and _OLD_ROBOT_KEYS & set(data):
            old = sorted(_OLD_ROBOT_KEYS & set(data))
            raise ValueError(f"{', '.join(old)}: the robot is now one address; write {_new_form(data)}")
        return data

    @field_validator("address")
    @classmethod
    def _address(cls, value: str) -> str:
        try:
            parse_robot_address(value)
        except ConfigError as exc:
            raise ValueError(str(exc)) from None
        return value

    @model_validator(mode="after")
    def _options_fit(self) -> RobotConfig:
        target = self.target()
        if self.token_file is not None and not isinstance(target, HttpAddress):
            raise ValueError(f"token_file is for an http(s):// MCP server, not {self.address!r}")
        if self.manifests is not None and isinstance(target, HttpAddress | StdioAddress):
            raise ValueError(f"manifests apply to a robot served here (sim:// or a middleware URI); the MCP "
                             f"server at {self.address!r} uses its own")
        return self

    def target(self) -> RobotAddress:
        """The parsed address."""
        return parse_robot_address(self.address)

    def local(self, command: str) -> LocalAddress:
        """The parsed address, which must be a robot run in this process (for `command`)."""
        target = self.target()
        if isinstance(target, HttpAddress | StdioAddress):
            raise ConfigError(f"{command} needs the robot's nodes in this process: give sim:// or a middleware "
                              f"URI (e.g. zenoh://127.0.0.1:7447), not the MCP server {self.address!r}")
        return target

    def describe(self) -> str:
        target = self.target()
        return f"{target} (embedded)" if isinstance(target, LocalAddress) else str(target)


def _new_form(old: Mapping[str, Any]) -> str:
    """The ``[robot]`` lines an old-style section means."""
    speed = old.get("sim_speed")
    address = old.get("server") or old.get("middleware") or (
        f"sim://?speed={speed:g}" if isinstance(speed, int | float) else "sim://")
    lines = [f'address = "{address}"'] + [f'{key} = "{old[key]}"' for key in ("manifests", "token_file") if key in old]
    return "; ".join(lines)


# What serves a url backend's model; sets its deadlines (robovoice.llm.base.DEADLINES_BY_KIND).
BackendKind = Literal["local-cpu", "edge-gpu", "cloud"]


def kind_for_url(url: str) -> BackendKind:
    """The kind a URL backend is taken to be when the config does not say: a server on this
    machine runs on its CPU; https is a hosted API; anything else a GPU server nearby."""
    parts = urlsplit(url)
    host = (parts.hostname or "").lower()
    if host == "localhost" or host == "::1" or host.startswith("127."):
        return "local-cpu"
    return "cloud" if parts.scheme == "https" else "edge-gpu"


class BackendConfig(_Frozen):
    """One ``[[llm.backends]]`` entry. A url backend's `kind` (default: `kind_for_url`) gives
    its deadlines (`DEADLINES_BY_KIND`); `connect_s` / `first_token_s` override two of them
    and, left out, are filled in from the kind, so they always hold the values in force."""

    url: str | None = None
    model: str | None = None
    kind: BackendKind | None = None
    local: bool = False
    model_path: Path | None = None
    api_key_env: str | None = None
    api_key_file: Path | None = None
    accepts_audio: bool = False
    connect_s: float | None = Field(default=None, gt=0)
    first_token_s: float | None = Field(default=None, gt=0)
    extra_body: dict[str, Any] = Field(default_factory=dict)

    @model_validator(mode="before")
    @classmethod
    def _kind_defaults(cls, data: Any) -> Any:
        if not isinstance(data, Mapping) or not isinstance(data.get("url"), str) or data.get("local"):
            return data  # a local backend, or one the checks below reject
        from robovoice.llm.base import DEADLINES_BY_KIND  # robovoice.llm imports this module

        kind = data.get("kind") or kind_for_url(data["url"])
        if kind not in DEADLINES_BY_KIND:
            return data  # the field check names the accepted kinds
        defaults = DEADLINES_BY_KIND[kind]
        return {"connect_s": defaults.connect_s, "first_token_s": defaults.first_token_s, **data, "kind": kind}

    def deadlines(self) -> Deadlines | None:
        """A url backend's deadlines: its kind's, with `connect_s` / `first_token_s` from the file.
        A local backend's: the embedded model's, with `first_token_s` from the file (None: unchanged)."""
        from robovoice.llm.base import DEADLINES_BY_KIND, LOCAL_DEADLINES

        if self.local:
            return dataclasses.replace(LOCAL_DEADLINES, first_token_s=self.first_token_s) if self.first_token_s \
                else None
        if self.kind is None:
            return None
        return dataclasses.replace(DEADLINES_BY_KIND[self.kind], connect_s=self.connect_s or 0.0,
                                   first_token_s=self.first_token_s or 0.0)

    @field_validator("url")
    @classmethod
    def _url(cls, value: str | None) -> str | None:
        if value is not None:
            try:
                check_http_url(value, "url", example="http://edge-server:8000/v1",
                               secret_fix="give the API key with api_key_env or api_key_file "
                                          "(--api-key-env, --api-key-file)")
            except ConfigError as exc:
                raise ValueError(str(exc).removeprefix("url: ")) from None
        return value

    @model_validator(mode="after")
    def _kind(self) -> BackendConfig:
        if self.local == bool(self.url):
            raise ValueError("each backend needs either `url` (an OpenAI-compatible server) or `local = true`")
        if self.api_key_env and self.api_key_file:
            raise ValueError("give the API key as api_key_env or api_key_file, not both")
        if self.local:
            misplaced = [name for name in ("model", "kind", "api_key_env", "api_key_file", "connect_s")
                         if getattr(self, name) is not None] + (["accepts_audio"] if self.accepts_audio else []) + (
                ["extra_body"] if self.extra_body else [])
            if misplaced:
                raise ValueError(f"{', '.join(misplaced)}: for url backends only; a local backend takes model_path")
        elif self.model_path is not None:
            raise ValueError("model_path is for `local = true` backends; a url backend names its `model`")
        if self.model_path is not None and not self.model_path.expanduser().is_file():
            raise ValueError(f"model_path {str(self.model_path)!r} is not a file; give the path of a GGUF model, "
                             f"or leave it out for the embedded model")
        return self


class LLMConfig(_Frozen):
    backends: tuple[BackendConfig, ...] = ()


# the log-probability thresholds of [voice]: default, what a lower one does, and the switch that turns it off
_LOGPROB_KEYS = {
    "confidence_min_logprob": ("-0.6", "turns fewer transcripts away", "confidence_check"),
    "confirm_below_logprob": ("-0.4", "asks less often", "confirm_doubtful"),
}


class VoiceConfig(_Frozen):
    """``[voice]``: the voice pipeline's settings, and the one place their defaults and limits
    live (`robovoice.voice.config.PipelineConfig.from_config` turns them into the pipeline's
    runtime settings; docs/voice.md says what each does). Times in seconds unless named ``_ms``."""

    wake_model: str = "hey_jarvis"
    # what the wake word says, for stripping it from transcripts and for speech-to-text hints;
    # default: the bundled model's name as words ("hey_mycroft" -> "hey mycroft")
    wake_phrase: str | None = None
    # 0.6, not openWakeWord's 0.5: the highest of 8 offsets raises talk without the phrase to
    # 0.49 (45 min, docs/voice.md "Wake word at every offset"); wake phrases score over 0.7 or under 0.5
    wake_threshold: float = Field(default=0.6, gt=0, lt=1)
    # a score from this up to wake_threshold wakes the robot only if the transcript names it
    # exactly ("Jarvis", not "Travis"): espeak-ng voices in noise that the model scores 0.1-0.5
    # (docs/voice.md "Unsure wake words"); 0 turns it off
    wake_unsure_threshold: float = Field(default=0.1, ge=0, lt=1)
    # 10 ms offsets the wake word is scored at (audio.wake.OpenWakeWordDetector): 8 catches a
    # borderline voice wherever the microphone's frames start; 1 is openWakeWord's own
    wake_phases: Literal[1, 2, 4, 8] = 8
    end_of_turn_silence_ms: int = Field(default=500, ge=100)
    max_utterance_s: float = Field(default=15.0, gt=0)
    # turn-taking: the command after a wake word said alone; answering the robot's question
    # without the wake word (always, not only after a question, with follow_up_always)
    command_timeout_s: float = Field(default=6.0, ge=0)
    follow_up_s: float = Field(default=6.0, ge=0)
    follow_up_always: bool = False
    wake_slack_s: float = Field(default=0.6, ge=0)  # a wake word this close after an utterance belongs to it
    stop_max_s: float = Field(default=4.0, ge=0)  # longer utterances are never checked for a spoken stop
    playback_tail_s: float = Field(default=0.3, ge=0)  # the echo of playback lasts this long
    # self-voice rejection
    echo_cancellation: bool = True
    echo_partitions: int = Field(default=8, ge=1)
    echo_step: float = Field(default=0.5, gt=0, le=1.5)
    near_end_margin_db: float = 6.0
    playback_wake_threshold: float = Field(default=0.7, gt=0, le=1)
    playback_match_score: float = Field(default=0.2, ge=0, le=1)
    # spoken output
    progress_interval_s: float = Field(default=8.0, ge=0)  # at most one progress line per this long
    stop_reply: str = "Stopped."  # after a spoken stop (unless the stop tool's manifest says otherwise)
    stop_failed_reply: str = "I could not stop the robot!"
    speech_queue: int = Field(default=8, ge=1)  # sentences queued for speech
    # said once per turn when nothing else would be heard this long after the user's words end
    # (a model still reading its prompt); "" = never
    one_moment: str = "One moment."
    one_moment_after_s: float = Field(default=1.5, gt=0)
    stop_timeout_s: float = Field(default=5.0, gt=0)  # the stop tool's answer, at most
    # using the end-of-turn silence (docs/voice.md): a shorter silence after a complete
    # request, and the model prefilled (and its tool call decoded) on the speculative transcript
    early_end: bool = True
    early_end_silence_ms: int = 300
    speculative_prefill: bool = True
    speculative_decode: bool = True
    # a command transcript whose mean token log-probability is below this is turned away
    # ("Sorry, I didn't catch that."); -0.6 was chosen on the dev audio (docs/judgement.md)
    confidence_check: bool = True
    confidence_min_logprob: float = -0.6
    # a command whose speech is less than this many dB above the noise around it is turned
    # away ("Sorry, it is too noisy ..."): Whisper hears commands drowned in noise word for
    # word and sure of them; 6 was chosen on the dev audio (docs/judgement.md "Too noisy to act on")
    confidence_min_snr_db: float = Field(default=6.0, ge=-20.0, le=40.0)
    # a tool with a confirm question ("Shall I call Anna?") is asked about, not run, on a
    # command transcript below this (a transcript in doubt); -0.4 was chosen on the dev audio
    confirm_doubtful: bool = True
    confirm_below_logprob: float = -0.4
    # speech-to-text: Whisper tiny.en (takes vocabulary hints), Moonshine base-en, or none
    # (only with an audio-capable model)
    stt: Literal["whisper", "moonshine", "none"] = "whisper"
    vocabulary: tuple[str, ...] = ()  # extra words for speech-to-text (names, places)

    @field_validator("early_end_silence_ms")
    @classmethod
    def _early_end_silence(cls, value: int) -> int:
        if not 50 <= value <= 5000:
            raise ValueError(f"early_end_silence_ms = {value}: give milliseconds from 50 to 5000, shorter than "
                             f"end_of_turn_silence_ms (default 300), or set early_end = false")
        return value

    @field_validator("confidence_min_logprob", "confirm_below_logprob")
    @classmethod
    def _min_logprob(cls, value: float, info: ValidationInfo) -> float:
        if not -10.0 <= value < 0.0:  # a mean log-probability is <= 0; below -10 nothing is ever turned away
            default, lower, switch = _LOGPROB_KEYS[str(info.field_name)]
            raise ValueError(f"{info.field_name} = {value}: give a mean token log-probability from -10 up to "
                             f"(not including) 0 (default {default}; lower {lower}), or set {switch} = false")
        return value

    @model_validator(mode="after")
    def _unsure_is_lower(self) -> VoiceConfig:
        if self.wake_unsure_threshold >= self.wake_threshold:
            raise ValueError(f"wake_unsure_threshold = {self.wake_unsure_threshold} is not under wake_threshold = "
                             f"{self.wake_threshold}: give a lower one (default 0.1), or 0 to turn it off")
        return self

    @model_validator(mode="after")
    def _early_end_is_shorter(self) -> VoiceConfig:
        if self.early_end and self.early_end_silence_ms >= self.end_of_turn_silence_ms:
            raise ValueError(f"early_end_silence_ms = {self.early_end_silence_ms} is not shorter than "
                             f"end_of_turn_silence_ms = {self.end_of_turn_silence_ms}: give a shorter one "
                             f"(default 300), or set early_end = false")
        return self

    @property
    def spoken_wake_phrase(self) -> str:
        """`wake_phrase`, or the wake model's name as words ("hey_jarvis", ".../okay_robot_v0.2.onnx")."""
        if self.wake_phrase is not None:
            return self.wake_phrase
        return re.sub(r"_v[\d.]+$", "", PurePath(self.wake_model).stem).replace("_", " ")


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
        raise ConfigError(validation_message(exc, str(path))) from None


def validation_message(exc: ValidationError, source: str) -> str:
    """One line per problem: the source, the field (``robot.address``) and what to do."""
    def one(error: Any) -> str:
        where = ".".join(str(p) for p in error["loc"])
        message = str(error["msg"]).removeprefix("Value error, ")
        value = "" if error["type"] in ("value_error", "missing") else f" (got {error.get('input')!r})"
        return f"{where}: {message}{value}" if where else message + value

    return f"{source}: " + "; ".join(one(e) for e in exc.errors())


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
