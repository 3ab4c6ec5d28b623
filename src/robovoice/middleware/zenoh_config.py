"""`zenoh://` URIs and the Zenoh configuration they stand for (see docs/zenoh.md).

    zenoh://                                  peer, rendezvous on tcp/127.0.0.1:7447 (below)
    zenoh://HOST:PORT                         peer, rendezvous on tcp/HOST:PORT
    zenoh://tcp/HOST:PORT                     the same, in Zenoh's own endpoint syntax (udp/ too)
    zenoh://[::1]:PORT                        an IPv6 host, in brackets
    zenoh://HOST:PORT?mode=client             client of the router/peer listening on HOST:PORT
    zenoh://?listen=tcp/127.0.0.1:7448&connect=tcp/127.0.0.1:7447   exactly these endpoints
    zenoh://?config=/path/zenoh.json5         a Zenoh config file; other parameters override it

Parameters: ``robot`` (key prefix ``robovoice/<robot>``, default ``default``), ``mode``
(peer | client | router), ``listen`` and ``connect`` (Zenoh endpoints; repeat the parameter
or separate with commas), ``scouting`` (off | multicast; default off), ``must_connect``
(true: fail at start unless a connect endpoint answers; always so in client mode),
``timeout`` (seconds to wait for a connect endpoint at start, default 3), ``config`` (a
Zenoh config file, which must exist). Endpoints are ``PROTOCOL/ADDRESS`` (``tcp/HOST:PORT``,
``udp/…``, ``tls/…``, ``quic/…``, ``ws/…``, ``unixsock-stream/PATH``, ...). Anything else —
an unknown parameter, an empty value, a path, a user name, a port out of range — is an error
that shows the right form: a URI that cannot mean what was written never starts a session
that meets nobody.

*Rendezvous*: every peer connects to ``HOST:PORT``; a peer that is given no ``listen`` also
listens there if the port is free (the first process on the machine takes it) and on an
ephemeral port of ``HOST``, so the peers that meet at the rendezvous learn each other's
addresses (gossip) and connect directly: the mesh survives the process that holds the port.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal, cast

from robovoice.errors import ConfigError
from robovoice.urls import check_port, query_options, split_host_port, split_uri

Mode = Literal["peer", "client", "router"]
DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 7447
DEFAULT_ROBOT = "default"
DEFAULT_TIMEOUT_S = 3.0
_KNOWN = {"robot", "mode", "listen", "connect", "scouting", "must_connect", "timeout", "config"}
_TRUE = {"1", "true", "yes", "on"}
_FALSE = {"0", "false", "no", "off"}
_MANY = ("listen", "connect")
# Zenoh's link protocols; the ones before the line take HOST:PORT
_IP_PROTOCOLS = ("tcp", "udp", "tls", "quic", "ws")
_PROTOCOLS = (*_IP_PROTOCOLS, "unixsock-stream", "unixpipe", "serial", "vsock")
_RENDEZVOUS_PROTOCOLS = ("tcp", "udp")
FORM = "zenoh://HOST:PORT (e.g. zenoh://127.0.0.1:7447, or zenoh://tcp/127.0.0.1:7447)"


@dataclass(frozen=True, slots=True)
class ZenohSettings:
    """What a `zenoh://` URI says, checked."""

    uri: str
    robot: str = DEFAULT_ROBOT
    mode: Mode = "peer"
    listen: tuple[str, ...] = ()
    connect: tuple[str, ...] = ()
    rendezvous: str | None = None
    """``tcp/HOST:PORT`` where peers meet (see the module docstring), or None."""
    multicast_scouting: bool = False
    must_connect: bool = False
    timeout_s: float = DEFAULT_TIMEOUT_S
    config_file: Path | None = None
    explicit: frozenset[str] = frozenset()
    """The parameters the URI names."""

    @classmethod
    def from_uri(cls, uri: str) -> ZenohSettings:
        parts = split_uri(uri, "zenoh URI")
        if parts.scheme != "zenoh" or not uri.startswith("zenoh://"):
            raise ConfigError(f"not a zenoh:// URI: {uri!r}; write {FORM}")
        if parts.fragment:
            raise ConfigError(f"{uri}: unexpected '#{parts.fragment}'; write {FORM}")
        query = query_options(parts, uri, _KNOWN, repeatable=_MANY)

        def one(name: str, default: str) -> str:
            values = query.get(name, [default])
            return values[0]

        def many(name: str) -> tuple[str, ...]:
            endpoints: list[str] = []
            for value in query.get(name, []):
                for ep in value.split(","):
                    if not ep.strip():
                        raise ConfigError(f"{uri}: an empty {name} endpoint in {value!r}; "
                                          f"write {name}=tcp/HOST:PORT[,tcp/HOST:PORT]")
                    endpoints.append(_endpoint(uri, name, ep.strip()))
            return tuple(endpoints)

        mode = one("mode", "peer")
        if mode not in ("peer", "client", "router"):
            raise ConfigError(f"{uri}: mode must be peer, client or router, not {mode!r}")
        scouting = one("scouting", "off")
        if scouting not in ("off", "multicast"):
            raise ConfigError(f"{uri}: scouting must be off or multicast, not {scouting!r}")
        robot = one("robot", DEFAULT_ROBOT)
        if not robot:
            raise ConfigError(f"{uri}: robot must not be empty")
        config = one("config", "")
        if "config" in query and not Path(config).expanduser().is_file():
            raise ConfigError(f"{uri}: config={config!r} is not a file; give the path of a Zenoh config "
                              f"(JSON5) file")
        listen, connect = many("listen"), many("connect")
        rendezvous = _rendezvous(uri, parts.netloc, parts.path, explicit=bool(listen or connect or config))
        if mode == "client" and rendezvous is None and not connect and not config:
            raise ConfigError(f"{uri}: client mode needs an endpoint to connect to (zenoh://HOST:PORT?mode=client)")
        return cls(
            uri=uri,
            robot=robot,
            mode=cast(Mode, mode),
            listen=listen,
            connect=connect,
            rendezvous=rendezvous,
            multicast_scouting=scouting == "multicast",
            must_connect=mode == "client" or _flag(uri, "must_connect", one("must_connect", "false")),
            timeout_s=_seconds(uri, one("timeout", str(DEFAULT_TIMEOUT_S))),
            config_file=Path(config).expanduser() if config else None,
            explicit=frozenset(query),
        )

    @property
    def connect_endpoints(self) -> tuple[str, ...]:
        extra = (self.rendezvous,) if self.rendezvous and self.rendezvous not in self.connect else ()
        return self.connect + extra

    @property
    def listen_endpoints(self) -> tuple[str, ...]:
        if self.listen or self.mode == "client" or self.rendezvous is None:
            return self.listen
        host = self.rendezvous.rsplit(":", 1)[0]
        return (self.rendezvous, f"{host}:0")

    def describe(self) -> str:
        """The endpoints, for error messages."""
        parts = [f"mode {self.mode}"]
        if self.connect_endpoints:
            parts.append(f"connect {', '.join(self.connect_endpoints)}")
        if self.listen_endpoints:
            parts.append(f"listen {', '.join(self.listen_endpoints)}")
        if self.config_file:
            parts.append(f"config {self.config_file}")
        return "; ".join(parts)

    def json5_entries(self) -> dict[str, object]:
        """The Zenoh config keys this URI sets. With a config file, only what the URI names
        explicitly (mode, scouting, endpoints, must_connect, timeout) overrides the file."""
        base = self.config_file is None
        entries: dict[str, object] = {}
        if base or "mode" in self.explicit:
            entries["mode"] = self.mode
        if base or "scouting" in self.explicit:
            entries["scouting/multicast/enabled"] = self.multicast_scouting
        if self.connect_endpoints:
            entries["connect/endpoints"] = list(self.connect_endpoints)
        if self.connect_endpoints or {"must_connect", "timeout"} & self.explicit:
            entries["connect/timeout_ms"] = int(self.timeout_s * 1000)
            entries["connect/exit_on_failure"] = self.must_connect
        if self.listen_endpoints:
            entries["listen/endpoints"] = list(self.listen_endpoints)
            # a rendezvous port taken by another process is expected; explicit ones must bind
            entries["listen/exit_on_failure"] = bool(self.listen)
        return entries


def _rendezvous(uri: str, netloc: str, path: str, *, explicit: bool) -> str | None:
    """``tcp/HOST:PORT`` from ``zenoh://HOST:PORT`` or Zenoh's ``zenoh://tcp/HOST:PORT``."""
    protocol = "tcp"
    if netloc in _PROTOCOLS and path in ("", "/"):  # zenoh://tcp/ : Zenoh's syntax with the address missing
        raise ConfigError(f"{uri}: expected zenoh://{netloc}/HOST:PORT; write {FORM}")
    if path not in ("", "/"):
        if netloc in _RENDEZVOUS_PROTOCOLS:  # zenoh://tcp/127.0.0.1:7447: Zenoh's endpoint syntax
            protocol, netloc = netloc, path[1:].rstrip("/")
            if not netloc or "/" in netloc:
                raise ConfigError(f"{uri}: expected zenoh://{protocol}/HOST:PORT; write {FORM}")
        elif netloc in _PROTOCOLS:
            raise ConfigError(f"{uri}: a {netloc}/ endpoint cannot be the rendezvous; give it explicitly, "
                              f"e.g. zenoh://?connect={netloc}{path}&mode=client")
        else:
            raise ConfigError(f"{uri}: unexpected path {path!r}; write {FORM}")
    if not netloc:
        return None if explicit else f"{protocol}/{DEFAULT_HOST}:{DEFAULT_PORT}"
    try:
        host, port = split_host_port(netloc, uri, FORM)
    except ConfigError as exc:
        raise ConfigError(f"{exc}; expected {FORM}, got {netloc!r}") from None
    return f"{protocol}/{host}:{DEFAULT_PORT if port is None else port}"


def _endpoint(uri: str, name: str, endpoint: str) -> str:
    """A Zenoh endpoint ``PROTOCOL/ADDRESS`` (port 0 allowed only for listen)."""
    protocol, sep, address = endpoint.partition("/")
    if not sep or protocol not in _PROTOCOLS or not address:
        raise ConfigError(f"{uri}: {name} endpoint {endpoint!r} is not PROTOCOL/ADDRESS; write e.g. "
                          f"{name}=tcp/127.0.0.1:7447 (protocols: {', '.join(_PROTOCOLS)})")
    if protocol in _IP_PROTOCOLS:
        hostport = address.split("#", 1)[0].split("?", 1)[0]
        host, colon, port = hostport.rpartition(":")
        if not colon or not host:
            raise ConfigError(f"{uri}: {name} endpoint {endpoint!r} needs HOST:PORT, e.g. {protocol}/127.0.0.1:7447")
        if ":" in host and not host.startswith("["):
            raise ConfigError(f"{uri}: {name} endpoint {endpoint!r}: write an IPv6 address in brackets, "
                              f"e.g. {protocol}/[::1]:7447")
        check_port(port, f"{uri}: {name} endpoint {endpoint!r}", allow_zero=name == "listen")
    return endpoint


def _flag(uri: str, name: str, value: str) -> bool:
    if value.lower() in _TRUE:
        return True
    if value.lower() in _FALSE:
        return False
    raise ConfigError(f"{uri}: {name} must be true or false, not {value!r}")


def _seconds(uri: str, value: str) -> float:
    try:
        seconds = float(value)
    except ValueError:
        raise ConfigError(f"{uri}: timeout must be a number of seconds, not {value!r}") from None
    if not 0 < seconds <= 600:
        raise ConfigError(f"{uri}: timeout must be between 0 and 600 seconds, not {seconds:g}")
    return seconds
