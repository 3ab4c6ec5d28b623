"""The robot address: one URI says which robot, resolved through one scheme table.

    sim://                        the simulated robot, embedded in this process (``sim`` alone too)
    sim://?speed=2&nodes=navigation,base
                                  options: speed (simulated seconds per real second, > 0),
                                  nodes (which sim nodes run; default all)
    memory://  zenoh://…  ros2://…
                                  any middleware URI (the schemes of `robovoice.middleware.ADAPTERS`):
                                  serve the nodes present on that middleware, in this process
    http://HOST:PORT/mcp  https://…/mcp
                                  a running MCP server (robovoice serve --transport http, or any other);
                                  its bearer token comes from a token file, never from the URI
    stdio:COMMAND                 an MCP server started as a child process, e.g.
                                  stdio:robovoice serve --robot sim

`parse_robot_address` turns the text into one of four frozen values (`RobotAddress`); an
unknown scheme lists the known ones. Manifests and token files are not part of the address:
they are fields of `robovoice.config.RobotConfig` (options ``--manifests``, ``--token-file``).
"""

from __future__ import annotations

import shlex
from collections.abc import Callable
from dataclasses import dataclass
from urllib.parse import urlsplit

from robovoice.errors import ConfigError, UnsupportedURIError
from robovoice.urls import check_http_url, positive_number, query_options

MAX_SIM_SPEED = 1000.0
SIM_OPTIONS = ("speed", "nodes")
HTTP_EXAMPLE = "http://127.0.0.1:8765/mcp"
STDIO_EXAMPLE = "stdio:robovoice serve --robot sim"
TOKEN_FIX = "put the token in a file and give it with --token-file F (or [robot] token_file)"


@dataclass(frozen=True, slots=True)
class SimAddress:
    """``sim://``: the simulated robot in this process. `speed` None: the command's default."""

    speed: float | None = None
    nodes: tuple[str, ...] | None = None

    def __str__(self) -> str:
        speed = None if self.speed is None else float(self.speed)
        options = ([f"speed={int(speed) if speed.is_integer() else speed!r}"] if speed is not None else []) + (
            [f"nodes={','.join(self.nodes)}"] if self.nodes is not None else [])
        return "sim://" + ("?" + "&".join(options) if options else "")


@dataclass(frozen=True, slots=True)
class MiddlewareAddress:
    """A middleware URI: the robot's nodes are on that middleware, served from this process."""

    uri: str

    @property
    def scheme(self) -> str:
        return urlsplit(self.uri).scheme

    def __str__(self) -> str:
        return self.uri


@dataclass(frozen=True, slots=True)
class HttpAddress:
    """``http(s)://host:port/path``: a running MCP server, streamable HTTP."""

    url: str

    def __str__(self) -> str:
        return self.url


@dataclass(frozen=True, slots=True)
class StdioAddress:
    """``stdio:COMMAND``: an MCP server started as a child process, spoken to over its stdio."""

    argv: tuple[str, ...]

    def __str__(self) -> str:
        return "stdio:" + shlex.join(self.argv)


RobotAddress = SimAddress | MiddlewareAddress | HttpAddress | StdioAddress
"""A parsed robot address (see the module docstring)."""

LocalAddress = SimAddress | MiddlewareAddress
"""An address whose robot side runs in this process (it can be served, checked, set up)."""


def _sim(text: str) -> SimAddress:
    parts = urlsplit(text)
    if parts.netloc or parts.path or parts.fragment:
        raise ConfigError(f"robot address {text!r}: sim:// takes no host or path; write e.g. sim://?speed=2")
    options = query_options(parts, f"robot address {text!r}", SIM_OPTIONS)
    speed = positive_number(options["speed"][0], f"robot address {text!r}: speed",
                            maximum=MAX_SIM_SPEED) if "speed" in options else None
    nodes = parse_sim_nodes(options["nodes"][0], f"robot address {text!r}: nodes") if "nodes" in options else None
    return SimAddress(speed, nodes)


def parse_sim_nodes(text: str, what: str) -> tuple[str, ...]:
    """A comma-separated list of sim node names, each known, none twice."""
    from robovoice.sim.robot import NODE_NAMES

    names = tuple(name.strip() for name in text.split(","))
    unknown = [name for name in names if name not in NODE_NAMES]
    if unknown or not names:
        raise ConfigError(f"{what}: unknown node(s) {', '.join(map(repr, unknown))}; "
                          f"the sim's nodes are {', '.join(NODE_NAMES)} (comma-separated)")
    if len(set(names)) != len(names):
        raise ConfigError(f"{what}: a node is named twice in {text!r}")
    return names


def _middleware(text: str) -> MiddlewareAddress:
    from robovoice.middleware import check_middleware_uri

    check_middleware_uri(text)
    return MiddlewareAddress(text)


def _http(text: str) -> HttpAddress:
    parts = check_http_url(text, "robot address", example=HTTP_EXAMPLE, secret_fix=TOKEN_FIX)
    if not parts.path:  # a server whose endpoint really is the root is written with its '/'
        raise ConfigError(f"robot address {text!r} names no MCP endpoint path; a robovoice server's is /mcp: "
                          f"{parts.scheme}://{parts.netloc}/mcp (write {text}/ for a server at the root)")
    if parts.fragment:
        raise ConfigError(f"robot address {text!r}: unexpected '#{parts.fragment}'; write e.g. {HTTP_EXAMPLE}")
    return HttpAddress(text)


def _stdio(text: str) -> StdioAddress:
    command = text[len("stdio:"):]
    if command.startswith("//"):
        raise ConfigError(f"robot address {text!r}: write stdio:COMMAND without '//', e.g. {STDIO_EXAMPLE}")
    try:
        argv = tuple(shlex.split(command))
    except ValueError as exc:
        raise ConfigError(f"robot address {text!r}: cannot split the command: {exc}") from None
    if not argv:
        raise ConfigError(f"robot address {text!r} needs a command, e.g. {STDIO_EXAMPLE}")
    return StdioAddress(argv)


_OWN_SCHEMES: dict[str, Callable[[str], RobotAddress]] = {
    "sim": _sim, "http": _http, "https": _http, "stdio": _stdio,
}


def robot_schemes() -> dict[str, Callable[[str], RobotAddress]]:
    """The scheme table: the own schemes plus every middleware adapter's (read now, so an
    adapter registered later, such as ``ros2``, is included)."""
    from robovoice.middleware import ADAPTERS

    table = dict(_OWN_SCHEMES)
    for scheme in ADAPTERS:
        if scheme in table:
            raise ConfigError(f"middleware scheme {scheme!r} clashes with a robot address scheme")
        table[scheme] = _middleware
    return table


def known_forms() -> list[str]:
    """The schemes as a user writes them, for error messages."""
    return [f"{s}:" if s == "stdio" else f"{s}://" for s in robot_schemes()]


def parse_robot_address(text: str) -> RobotAddress:
    """The address `text` means; `ConfigError` (an `UnsupportedURIError` for an unknown scheme)
    that names the value and the right form otherwise. ``sim`` alone is ``sim://``."""
    text = text.strip()
    if text == "sim":
        return SimAddress()
    try:
        scheme = urlsplit(text).scheme if ":" in text else ""
        parse = robot_schemes().get(scheme)
        if parse is None:
            raise UnsupportedURIError(text, known_forms(), what="robot address")
        if scheme != "stdio" and not text.startswith(f"{scheme}://"):
            raise ConfigError(f"robot address {text!r}: write {scheme}://… (with '//')")
        return parse(text)
    except ValueError as exc:  # urlsplit: an unclosed [IPv6] bracket, a bad port, …
        raise ConfigError(f"robot address {text!r} is not a valid URI: {exc}") from None


def parse_middleware_uri(text: str, what: str = "middleware URI") -> MiddlewareAddress:
    """`text` as a middleware URI (not sim://, not an MCP server)."""
    address = parse_robot_address(text)
    if not isinstance(address, MiddlewareAddress):
        from robovoice.middleware import ADAPTERS

        raise ConfigError(f"{what} {text!r} is not a middleware URI; the middleware schemes are "
                          f"{', '.join(f'{s}://' for s in ADAPTERS)}")
    return address


def with_sim_speed(address: RobotAddress, speed: float | None) -> RobotAddress:
    """`address` with its sim speed filled in where it gives none (others unchanged)."""
    if isinstance(address, SimAddress) and address.speed is None and speed is not None:
        return SimAddress(float(speed), address.nodes)
    return address
