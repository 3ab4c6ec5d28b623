"""Robot addresses (robovoice.address) and the shared value checks (robovoice.urls)."""

from __future__ import annotations

import pytest

from robovoice.address import (
    HttpAddress,
    MiddlewareAddress,
    SimAddress,
    StdioAddress,
    known_forms,
    parse_middleware_uri,
    parse_robot_address,
    with_sim_speed,
)
from robovoice.errors import ConfigError, UnsupportedURIError
from robovoice.middleware import ADAPTERS, check_middleware_uri, open_middleware
from robovoice.urls import check_port, positive_number, split_host_port


@pytest.mark.parametrize("text, expected", [
    ("sim", SimAddress()),
    ("sim://", SimAddress()),
    (" sim:// ", SimAddress()),
    ("sim://?speed=2", SimAddress(2.0)),
    ("sim://?speed=0.5&nodes=navigation,base", SimAddress(0.5, ("navigation", "base"))),
    ("sim://?speed=1.23456789", SimAddress(1.23456789)),
    ("memory://", MiddlewareAddress("memory://")),
    ("zenoh://127.0.0.1:7447?robot=r1", MiddlewareAddress("zenoh://127.0.0.1:7447?robot=r1")),
    ("zenoh://tcp/127.0.0.1:7447", MiddlewareAddress("zenoh://tcp/127.0.0.1:7447")),
    ("http://127.0.0.1:8765/mcp", HttpAddress("http://127.0.0.1:8765/mcp")),
    ("https://robot.local/mcp", HttpAddress("https://robot.local/mcp")),
    ("http://127.0.0.1:9000/", HttpAddress("http://127.0.0.1:9000/")),  # a server at the root, said explicitly
    ("http://[::1]:8765/mcp", HttpAddress("http://[::1]:8765/mcp")),
    ("stdio:robovoice serve --robot sim", StdioAddress(("robovoice", "serve", "--robot", "sim"))),
    ("stdio:'my server' --flag", StdioAddress(("my server", "--flag"))),
])
def test_addresses_parse_to_one_value_each(text: str, expected: object) -> None:
    address = parse_robot_address(text)
    assert address == expected
    assert parse_robot_address(str(address)) == address  # the canonical form reads back the same


@pytest.mark.parametrize("text, message", [
    ("turtle://", "supported schemes are sim://, http://, https://, stdio:, memory://, zenoh://"),
    ("kitchen", "supported schemes"),
    ("", "supported schemes"),
    ("sim://?speed=-1", "speed must be greater than 0"),
    ("sim://?speed=0", "speed must be greater than 0"),
    ("sim://?speed=nan", "speed must be greater than 0"),
    ("sim://?speed=fast", "speed must be a number"),
    ("sim://?speed=5000", "at most 1000"),
    ("sim://?sped=2", "unknown option(s) sped; known: nodes, speed"),
    ("sim://?speed=1&speed=2", "given 2 times"),
    ("sim://?speed", "needs a value"),
    ("sim://?nodes=navigation,kitchen", "unknown node(s) 'kitchen'"),
    ("sim://?nodes=base,base", "named twice"),
    ("sim://robot", "takes no host or path"),
    ("sim:", "write sim://"),
    ("zenoh:127.0.0.1", "write zenoh://"),
    ("memory://bus", "write memory://"),
    ("memory://?x=1", "write memory://"),
    ("zenoh://127.0.0.1:99999", "port must be a number from 1 to 65535"),
    ("zenoh://tls/127.0.0.1:7447", "cannot be the rendezvous"),
    ("ros2://?domain_id=999", "domain_id must be 0..232"),  # checked as an address, before ROS 2 is loaded
    ("http://127.0.0.1:8765", "names no MCP endpoint path"),
    ("http://127.0.0.1:0/mcp", "port must be a number from 1 to 65535"),
    ("http://127.0.0.1:70000/mcp", "port must be"),
    ("http://:8765/mcp", "the host is empty"),
    ("http:///mcp", "has no host"),
    ("http://user:secret@robot/mcp", "--token-file"),
    ("http://robot/mcp?token=abc", "no secrets in the URI"),
    ("http://robot/mcp?api_key=abc", "no secrets in the URI"),
    ("http://robot/mcp#frag", "unexpected '#frag'"),
    ("http://ro bot/mcp", "not a host name"),
    ("http://::1:8765/mcp", "in brackets"),
    ("stdio:", "needs a command"),
    ("stdio:   ", "needs a command"),
    ("stdio://robovoice serve", "without '//'"),
    ("stdio:robovoice 'serve", "cannot split"),
])
def test_bad_addresses_say_what_and_how(text: str, message: str) -> None:
    with pytest.raises(ConfigError) as info:
        parse_robot_address(text)
    assert message in str(info.value)


def test_an_unknown_scheme_lists_the_known_ones_from_the_one_table() -> None:
    with pytest.raises(UnsupportedURIError) as info:
        parse_robot_address("ftp://robot")
    assert info.value.supported == known_forms()
    assert {f"{scheme}://" for scheme in ADAPTERS} <= set(info.value.supported)  # middleware schemes come along
    assert "robot address 'ftp://robot'" in str(info.value)


def test_middleware_uris_only_where_a_middleware_is_meant() -> None:
    assert parse_middleware_uri("zenoh://") == MiddlewareAddress("zenoh://")
    for other in ("sim://", "http://127.0.0.1:1/mcp", "stdio:x"):
        with pytest.raises(ConfigError, match="is not a middleware URI; the middleware schemes are memory://"):
            parse_middleware_uri(other, "--middleware")
    with pytest.raises(UnsupportedURIError, match="middleware URI 'zenoh'"):
        check_middleware_uri("zenoh")
    with pytest.raises(UnsupportedURIError, match="supported schemes are memory://"):
        open_middleware("mqtt://broker")


def test_sim_speed_fills_only_an_unset_sim_speed() -> None:
    assert with_sim_speed(SimAddress(), 3.0) == SimAddress(3.0)
    assert with_sim_speed(SimAddress(2.0), 3.0) == SimAddress(2.0)
    assert with_sim_speed(MiddlewareAddress("memory://"), 3.0) == MiddlewareAddress("memory://")


def test_value_checks() -> None:
    assert split_host_port("[::1]:80", "x", "e") == ("[::1]", 80)
    assert split_host_port("robot.local", "x", "e") == ("robot.local", None)
    assert check_port("0", "x", allow_zero=True) == 0
    assert positive_number("2.5", "speed") == 2.5
    for bad in ("[::1", "[::1]x", "a@b:1", "h:-1", "h:"):
        with pytest.raises(ConfigError):
            split_host_port(bad, "x", "e")
    with pytest.raises(ConfigError, match="from 1 to 65535, not '0'"):
        check_port("0", "x")
    with pytest.raises(ConfigError, match="greater than 0"):
        positive_number("inf", "speed")
