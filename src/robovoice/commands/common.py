"""Options shared by the commands that talk to a robot and an LLM (serve, tools, call,
check-manifests, chat, eval, assist, ...): one robot address, one config, strict values.

    --robot ADDRESS      any robot address (robovoice.address): sim (= sim://), sim://?speed=2,
                         memory://, zenoh://HOST:PORT, http(s)://HOST:PORT/mcp, stdio:COMMAND
    --middleware URI     the same, for a middleware URI (the documented spelling of old)
    --server URL         the same, for an MCP server: http(s)://HOST:PORT/mcp or stdio:COMMAND
    --manifests DIR, --token-file F, --sim-speed X   fields of the robot config
"""

from __future__ import annotations

import argparse
import logging
import math
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from urllib.parse import urlsplit

from pydantic import ValidationError

from robovoice.address import (
    HttpAddress,
    RobotAddress,
    SimAddress,
    StdioAddress,
    parse_middleware_uri,
    parse_robot_address,
    with_sim_speed,
)
from robovoice.assistant.prompt import SYSTEM_PROMPT
from robovoice.config import BackendConfig, Config, LLMConfig, RobotConfig, load_config, validation_message
from robovoice.errors import ConfigError
from robovoice.llm.base import LLMBackend, ToolSpec
from robovoice.llm.failover import FailoverBackend
from robovoice.llm.registry import ACCEPTED_FORMS, BackendSpec, api_key_from, chain_from_specs

log = logging.getLogger(__name__)



def address_forms() -> str:
    """The address forms for help texts, middleware schemes from the adapter table."""
    from robovoice.middleware import ADAPTERS

    middleware = ", ".join(f"{scheme}://…" for scheme in ADAPTERS)
    return f"sim (= sim://), sim://?speed=2, a middleware URI ({middleware}), http(s)://HOST:PORT/mcp, stdio:COMMAND"


# --- strict option values ----------------------------------------------------------------


def _number(kind: Callable[[str], float], low: float, *, inclusive: bool, what: str) -> Callable[[str], float]:
    def parse(text: str) -> float:
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {what}, not {text!r}") from None
        if not math.isfinite(value) or value < low or (value == low and not inclusive):
            raise argparse.ArgumentTypeError(f"expected {what}, not {text!r}")
        return value

    return parse


positive_float = _number(float, 0.0, inclusive=False, what="a number greater than 0")
non_negative_float = _number(float, 0.0, inclusive=True, what="a number of seconds, 0 or more")


def positive_int(text: str) -> int:
    if not text.strip().isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number of at least 1, not {text!r}")
    return int(text)


def port_number(text: str) -> int:
    if not text.strip().isdigit() or int(text) > 65535:
        raise argparse.ArgumentTypeError(f"expected a port from 0 (any free port) to 65535, not {text!r}")
    return int(text)


def host_name(text: str) -> str:
    if not text.strip() or any(c.isspace() for c in text):
        raise argparse.ArgumentTypeError(f"expected a host name or address, e.g. 127.0.0.1, not {text!r}")
    return text


def existing_file(text: str) -> Path:
    path = Path(text).expanduser()
    if not path.is_file():
        raise argparse.ArgumentTypeError(f"no such file: {text}")
    return path


# --- the robot ----------------------------------------------------------------------------


def add_robot_args(parser: argparse.ArgumentParser, *, default_speed: float = 1.0, token_file: bool = True,
                   config: bool = False, required_hint: str = "default: the config's [robot] address, else sim://"
                   ) -> None:
    """The robot options. `token_file`: offer --token-file (an http(s) robot's token; `serve`
    has its own). `config`: offer --config (commands without the LLM options)."""
    group = parser.add_argument_group(f"robot ({required_hint})")
    where = group.add_mutually_exclusive_group()
    where.add_argument("--robot", metavar="ADDRESS", help=f"which robot: {address_forms()}")
    where.add_argument("--middleware", metavar="URI", help="serve the nodes present on this middleware URI")
    where.add_argument("--server", metavar="URL",
                       help="a running robot's MCP server: http(s)://HOST:PORT/mcp, or 'stdio:<command>'")
    group.add_argument("--manifests", type=Path, metavar="DIR",
                       help="manifests that replace the nodes' own (DIR/<node>/mcp.json or DIR/<node>.mcp.json)")
    if token_file:
        group.add_argument("--token-file", type=Path, metavar="F", dest="robot_token_file",
                           help="the bearer token of an http(s):// robot address")
    group.add_argument("--sim-speed", type=positive_float, metavar="X",
                       help=f"simulated seconds per real second for sim:// (default {default_speed:g}; "
                            f"same as sim://?speed=X)")
    if config:
        group.add_argument("--config", type=Path, metavar="FILE", help="a robovoice.toml (see docs/llm.md)")
    parser.set_defaults(default_sim_speed=default_speed)


def config_from_args(args: argparse.Namespace) -> Config:
    return load_config(getattr(args, "config", None))


def address_from_args(args: argparse.Namespace) -> RobotAddress | None:
    """The address given by --robot, --middleware or --server (None: none given)."""
    if args.robot:
        return parse_robot_address(args.robot)
    if args.middleware:
        return parse_middleware_uri(args.middleware, "--middleware")
    if getattr(args, "server", None):
        address = parse_robot_address(args.server)
        if not isinstance(address, HttpAddress | StdioAddress):
            raise ConfigError(f"--server takes an MCP server, http(s)://HOST:PORT/mcp or stdio:COMMAND, not "
                              f"{args.server!r}; give other robots with --robot")
        return address
    return None


def robot_config(**fields: object) -> RobotConfig:
    """A `RobotConfig` from command-line values; a bad value is a `ConfigError` naming it."""
    try:
        return RobotConfig.model_validate(fields)
    except ValidationError as exc:
        raise ConfigError(validation_message(exc, "robot options")) from None


def robot_config_from_args(args: argparse.Namespace, config: Config | None = None) -> RobotConfig:
    """The robot: the address on the command line (with its --manifests / --token-file), else the
    config file's ``[robot]`` (options on the command line override its fields), else ``sim://``.
    A sim address without a speed gets --sim-speed, else the command's default."""
    given = address_from_args(args)
    manifests: Path | None = args.manifests
    token_file: Path | None = getattr(args, "robot_token_file", None)  # `serve --token-file` is the server's own
    if given is None:
        section = (config or config_from_args(args)).robot
        given = section.target()
        manifests = manifests or section.manifests
        token_file = token_file or section.token_file
    speed: float | None = args.sim_speed
    if speed is not None:
        if not isinstance(given, SimAddress):
            raise ConfigError(f"--sim-speed applies to the simulated robot (sim://), not {given}")
        if given.speed is not None and given.speed != speed:
            raise ConfigError(f"two sim speeds: --sim-speed {speed:g} and {given}; give one")
    address = with_sim_speed(given, speed if speed is not None else args.default_sim_speed)
    return robot_config(address=str(address), manifests=manifests, token_file=token_file)


# --- the language model -------------------------------------------------------------------


def add_llm_args(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("language model (default: the embedded local model)")
    group.add_argument("--llm", action="append", metavar="SPEC",
                       help="'local', 'local:/path/model.gguf' or an OpenAI-compatible base URL "
                            "(http://host:8000/v1); repeat for a failover chain, tried in order")
    group.add_argument("--model", help="model name for URL backends (or write URL#model)")
    group.add_argument("--api-key-env", metavar="VAR", help="environment variable holding the API key")
    group.add_argument("--api-key-file", type=Path, metavar="F", help="file holding the API key")
    group.add_argument("--audio-input", action="store_true",
                       help="URL backends accept input_audio (an audio-capable model such as Qwen3-Omni)")
    group.add_argument("--config", type=Path, metavar="FILE", help="a robovoice.toml (see docs/llm.md)")


def llm_config_from_args(args: argparse.Namespace, config: Config) -> LLMConfig:
    """The backends: from --llm (in order, with --model, --api-key-* and --audio-input for the
    URL ones), else the config file's ``[[llm.backends]]``, else the local model. The command
    line makes the same `BackendConfig`s a config file does, checked the same way."""
    if not args.llm:
        return config.llm if config.llm.backends else LLMConfig(backends=(BackendConfig(local=True),))
    url_options = {"model": args.model, "api_key_env": args.api_key_env, "api_key_file": args.api_key_file,
                   "accepts_audio": args.audio_input}
    backends: list[BackendConfig] = []
    for spec in (text.strip() for text in args.llm):
        if spec == "local" or spec.startswith("local:"):
            path = spec.removeprefix("local").removeprefix(":").strip()
            if spec.startswith("local:") and not path:
                raise ConfigError(f"--llm {spec!r}: accepted forms: {'; '.join(ACCEPTED_FORMS)}")
            fields: dict[str, object] = {"local": True, "model_path": Path(path).expanduser() if path else None}
        elif urlsplit(spec).scheme in ("http", "https"):
            fields = {"url": spec, **url_options}
        else:
            raise ConfigError(f"--llm {spec!r}: accepted forms: {'; '.join(ACCEPTED_FORMS)}")
        try:
            backends.append(BackendConfig.model_validate(fields))
        except ValidationError as exc:
            raise ConfigError(validation_message(exc, f"--llm {spec}")) from None
    if all(b.local for b in backends):
        misplaced = [f"--{name.replace('_', '-')}".replace("accepts-audio", "audio-input")
                     for name, value in url_options.items() if value]
        if misplaced:
            raise ConfigError(f"{', '.join(misplaced)}: for URL backends (--llm http://HOST:PORT/v1) only")
    return LLMConfig(backends=tuple(backends))


def backend_spec(backend: BackendConfig, env: Mapping[str, str]) -> BackendSpec:
    """What one configured backend becomes at run time (its API key read now)."""
    if backend.local:
        return BackendSpec(f"local:{backend.model_path}" if backend.model_path else "local",
                           deadlines=backend.deadlines())
    assert backend.url is not None
    return BackendSpec(backend.url, model=backend.model, accepts_audio=backend.accepts_audio,
                       api_key=api_key_from(env, env_var=backend.api_key_env, key_file=backend.api_key_file),
                       extra_body=backend.extra_body, deadlines=backend.deadlines())


def backend_from_args(args: argparse.Namespace, config: Config | None = None) -> FailoverBackend:
    """The failover chain from --llm (in order), else the config file, else the local model."""
    llm = llm_config_from_args(args, config or config_from_args(args))
    env = os.environ  # API keys are named on the command line or in the config, read from here
    specs = [backend_spec(b, env) for b in llm.backends]
    try:
        return chain_from_specs(specs)
    except ConfigError:
        raise
    except ValueError as exc:
        raise ConfigError(str(exc)) from exc


async def warm_up(backend: LLMBackend, tools: list[ToolSpec], system_prompt: str = SYSTEM_PROMPT) -> None:
    """Load local models and cache the unchanging prompt prefix before the first turn."""
    from robovoice.llm.local import LocalLlamaBackend

    members = backend.backends if isinstance(backend, FailoverBackend) else (backend,)
    for member in members:
        if isinstance(member, LocalLlamaBackend):
            stats = await member.warm_up(system_prompt, tools)
            log.info("local model warm: %s", stats)
