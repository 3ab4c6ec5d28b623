"""The robot and LLM parts of the one config (robovoice.config): TOML → validated model, or a
`ConfigError` naming the file, the field, the value and the fix; and the command-line options
that build the same `RobotConfig`."""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import pytest

from robovoice.address import HttpAddress, MiddlewareAddress, SimAddress
from robovoice.commands.common import add_llm_args, add_robot_args, backend_from_args, robot_config_from_args
from robovoice.config import RobotConfig, load_config
from robovoice.errors import ConfigError
from robovoice.llm.openai_compat import OpenAICompatBackend


def _load(tmp_path: Path, text: str) -> RobotConfig:
    path = tmp_path / "robovoice.toml"
    path.write_text(text)
    return load_config(path).robot


def test_the_robot_is_one_address(tmp_path: Path) -> None:
    assert RobotConfig().target() == SimAddress()
    robot = _load(tmp_path, '[robot]\naddress = "zenoh://tcp/127.0.0.1:7447"\nmanifests = "m"\n')
    assert robot.target() == MiddlewareAddress("zenoh://tcp/127.0.0.1:7447") and robot.manifests == Path("m")
    token = _load(tmp_path, '[robot]\naddress = "https://robot.local/mcp"\ntoken_file = "t"\n')
    assert token.target() == HttpAddress("https://robot.local/mcp") and token.describe() == "https://robot.local/mcp"
    assert _load(tmp_path, '[robot]\naddress = "sim://?speed=2"\n').describe() == "sim://?speed=2 (embedded)"


@pytest.mark.parametrize("section, message", [
    ('robot = "sim"\nsim_speed = 3', 'write address = "sim://?speed=3"'),
    ('middleware = "zenoh://10.0.0.2:7447"\nmanifests = "m"',
     'write address = "zenoh://10.0.0.2:7447"; manifests = "m"'),
    ('server = "http://robot:8765/mcp"\ntoken_file = "t"', 'write address = "http://robot:8765/mcp"; token_file = "t"'),
    ('address = "zenoh://tcp/127.0.0.1:99999"', "robot.address: zenoh://tcp/127.0.0.1:99999: port must be"),
    ('address = "sim://?speed=-1"', "speed must be greater than 0"),
    ('address = "turtle://"', "supported schemes are sim://"),
    ('address = "sim://"\ntoken_file = "t"', "token_file is for an http(s):// MCP server, not 'sim://'"),
    ('address = "stdio:robovoice serve"\nmanifests = "m"', "manifests apply to a robot served here"),
    ('address = "sim://"\nspeed = 2', "robot.speed: Extra inputs are not permitted"),
])
def test_bad_robot_sections_name_the_field_and_the_fix(tmp_path: Path, section: str, message: str) -> None:
    with pytest.raises(ConfigError) as info:
        _load(tmp_path, f"[robot]\n{section}\n")
    assert str(info.value).startswith(str(tmp_path / "robovoice.toml")) and message in str(info.value)


@pytest.mark.parametrize("backend, message", [
    ('url = "http://edge:99999/v1"\nmodel = "m"', "port must be a number from 1 to 65535"),
    ('url = "http://:8000/v1"\nmodel = "m"', "the host is empty"),
    ('url = "ftp://edge/v1"\nmodel = "m"', "expected an http:// or https:// URL"),
    ('url = "http://user:key@edge/v1"\nmodel = "m"', "api_key_env or api_key_file"),
    ('url = "http://edge/v1?api_key=x"\nmodel = "m"', "no secrets in the URI"),
    ('url = "http://edge/v1"\napi_key_env = "K"\napi_key_file = "f"', "not both"),
    ('local = true\nmodel = "m"', "model: for url backends only"),
    ('local = true\naccepts_audio = true', "accepts_audio: for url backends only"),
    ('url = "http://edge/v1"\nmodel_path = "x.gguf"', "model_path is for `local = true` backends"),
    ('url = "http://edge/v1"\nconnect_s = -1', "connect_s: Input should be greater than 0"),
    ('local = true\nmodel_path = "/no/such/model.gguf"', "model_path '/no/such/model.gguf' is not a file"),
])
def test_bad_backends_name_the_field_and_the_fix(tmp_path: Path, backend: str, message: str) -> None:
    path = tmp_path / "robovoice.toml"
    path.write_text(f"[[llm.backends]]\n{backend}\n")
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert message in str(info.value)


def _args(*argv: str, default_speed: float = 1.0) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_robot_args(parser, default_speed=default_speed)
    add_llm_args(parser)
    return parser.parse_args(list(argv))


def test_the_command_line_makes_the_same_robot_config(tmp_path: Path) -> None:
    assert robot_config_from_args(_args()).target() == SimAddress(1.0)
    assert robot_config_from_args(_args(default_speed=10)).target() == SimAddress(10.0)
    assert robot_config_from_args(_args("--robot", "sim", "--sim-speed", "4")).target() == SimAddress(4.0)
    assert robot_config_from_args(_args("--robot", "sim://?speed=3", "--sim-speed", "3")).target() == SimAddress(3.0)
    assert robot_config_from_args(_args("--middleware", "memory://")).target() == MiddlewareAddress("memory://")
    server = robot_config_from_args(_args("--server", "http://robot:8765/mcp", "--token-file", "t"))
    assert server.target() == HttpAddress("http://robot:8765/mcp") and server.token_file == Path("t")
    config = tmp_path / "robovoice.toml"
    config.write_text('[robot]\naddress = "sim://?nodes=base"\n')
    from_file = robot_config_from_args(_args("--config", str(config), "--sim-speed", "2"))
    assert from_file.target() == SimAddress(2.0, ("base",))


def test_backend_deadlines_from_the_config_are_used(tmp_path: Path) -> None:
    config = tmp_path / "robovoice.toml"
    config.write_text('[[llm.backends]]\nurl = "http://edge:8000/v1"\nmodel = "m"\nconnect_s = 0.5\n'
                      'first_token_s = 20\n')
    chain = backend_from_args(_args("--config", str(config)))
    edge = chain.backends[0]
    assert isinstance(edge, OpenAICompatBackend)
    assert (edge.deadlines.connect_s, edge.deadlines.first_token_s) == (0.5, 20.0)


def test_url_options_need_a_url_backend() -> None:
    with pytest.raises(ConfigError, match="--model: for URL backends"):
        backend_from_args(_args("--llm", "local", "--model", "m"))
    with pytest.raises(ConfigError, match="names model 'a' and --model 'b'"):
        backend_from_args(_args("--llm", "http://edge:8000/v1#a", "--model", "b"))
    with pytest.raises(ConfigError, match="unexpected query"):
        backend_from_args(_args("--llm", "http://edge:8000/v1?x=1#m"))
    with pytest.raises(ConfigError, match="port must be"):
        backend_from_args(_args("--llm", "http://edge:0/v1#m"))
    with pytest.raises(ConfigError, match=re.escape("--llm local:/no/such.gguf: model_path '/no/such.gguf' is not")):
        backend_from_args(_args("--llm", "local:/no/such.gguf"))
    for spec in ("foo", "local:", "ftp://edge/v1#m"):
        with pytest.raises(ConfigError, match="accepted forms: 'local'"):
            backend_from_args(_args("--llm", spec))
    with pytest.raises(ConfigError) as info:
        backend_from_args(_args("--llm", "http://user:key@edge/v1#m"))
    assert str(info.value).startswith("--llm http://user:key@edge/v1#m: url: no user name or password in the URL")
    assert "--api-key-env" in str(info.value)


def test_the_command_line_makes_the_same_backend_configs(tmp_path: Path) -> None:
    (tmp_path / "x.gguf").write_bytes(b"GGUF")
    chain = backend_from_args(_args("--llm", "http://edge:8000/v1#omni", "--llm", f"local:{tmp_path}/x.gguf",
                                    "--audio-input"))
    edge, local = chain.backends
    assert isinstance(edge, OpenAICompatBackend) and edge.model == "omni" and edge.accepts_audio
    assert not local.accepts_audio and local.name == "local"
