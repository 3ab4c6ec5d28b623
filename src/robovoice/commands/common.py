"""Options shared by the commands that talk to a robot and an LLM (chat, eval, demo, assist)."""

from __future__ import annotations

import argparse
import logging
import os
from pathlib import Path

from robovoice.assistant.connect import RobotTarget
from robovoice.assistant.prompt import SYSTEM_PROMPT
from robovoice.config import Config, load_config
from robovoice.errors import ConfigError
from robovoice.llm.base import LLMBackend, ToolSpec
from robovoice.llm.failover import FailoverBackend
from robovoice.llm.registry import BackendSpec, api_key_from, chain_from_specs

log = logging.getLogger(__name__)


def add_robot_args(parser: argparse.ArgumentParser, *, default_speed: float = 1.0) -> None:
    group = parser.add_argument_group("robot (default: the embedded simulated robot)")
    where = group.add_mutually_exclusive_group()
    where.add_argument("--robot", choices=["sim"], help="run the simulated robot in this process")
    where.add_argument("--middleware", metavar="URI", help="serve the nodes on this middleware (memory://, zenoh://…)")
    where.add_argument("--server", metavar="URL",
                       help="a remote robot's MCP server: http(s)://host:port/mcp, or 'stdio:<command>'")
    group.add_argument("--manifests", type=Path, metavar="DIR", help="manifest folder (with --middleware)")
    group.add_argument("--token-file", type=Path, metavar="F", help="bearer token for --server over HTTP")
    group.add_argument("--sim-speed", type=float, default=default_speed, metavar="X",
                       help=f"simulated time speed-up (default {default_speed:g})")


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


def config_from_args(args: argparse.Namespace) -> Config:
    return load_config(getattr(args, "config", None))


def robot_target_from_args(args: argparse.Namespace, config: Config | None = None) -> RobotTarget:
    config = config or config_from_args(args)
    robot_cfg = config.robot
    if args.server or args.middleware or args.robot:
        return RobotTarget(robot=args.robot or ("sim" if not (args.server or args.middleware) else None),
                           middleware=args.middleware, manifests=args.manifests, server=args.server,
                           token_file=args.token_file, sim_speed=args.sim_speed)
    if robot_cfg.server or robot_cfg.middleware:
        return RobotTarget(robot=None, middleware=robot_cfg.middleware, manifests=robot_cfg.manifests,
                           server=robot_cfg.server, token_file=robot_cfg.token_file, sim_speed=robot_cfg.sim_speed)
    return RobotTarget(robot="sim", sim_speed=args.sim_speed)


def backend_from_args(args: argparse.Namespace, config: Config | None = None) -> FailoverBackend:
    """The failover chain from --llm (in order), else the config file, else the local model."""
    config = config or config_from_args(args)
    env = os.environ  # API keys are named on the command line or in the config, read from here
    if args.llm:
        key = api_key_from(env, env_var=args.api_key_env, key_file=args.api_key_file)
        specs = [
            BackendSpec(spec, model=args.model if spec.startswith("http") else None,
                        api_key=key if spec.startswith("http") else None,
                        accepts_audio=args.audio_input and spec.startswith("http"))
            for spec in args.llm
        ]
    elif config.llm.backends:
        specs = []
        for b in config.llm.backends:
            if b.local:
                specs.append(BackendSpec(f"local:{b.model_path}" if b.model_path else "local"))
            else:
                assert b.url is not None
                specs.append(BackendSpec(b.url, model=b.model, accepts_audio=b.accepts_audio,
                                         api_key=api_key_from(env, env_var=b.api_key_env, key_file=b.api_key_file),
                                         extra_body=b.extra_body))
    else:
        specs = [BackendSpec("local")]
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
