"""Streamable HTTP transport: the SDK's session manager under uvicorn, behind a guard.

Security defaults (DESIGN.md §8):

- binds 127.0.0.1 unless told otherwise, and refuses to bind any non-loopback address
  without a bearer token (`check_bind`);
- every request, on every path, passes `HttpGuard` first: its ``Host`` must name a
  loopback host or the configured one (else 421), its ``Origin``, when present, too (else
  403: DNS-rebinding protection), and with a token it must carry
  ``Authorization: Bearer <token>`` (else 401; compared with `hmac.compare_digest`).
"""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import ipaddress
import logging
import socket
from collections.abc import AsyncIterator, Iterable, Iterator
from contextlib import asynccontextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import uvicorn
from mcp.server.streamable_http_manager import StreamableHTTPASGIApp
from mcp.server.transport_security import TransportSecuritySettings
from starlette.applications import Starlette
from starlette.datastructures import Headers
from starlette.responses import PlainTextResponse
from starlette.routing import Route
from starlette.types import ASGIApp, Receive, Scope, Send

from robovoice.config import read_secret_file
from robovoice.errors import ConfigError
from robovoice.mcp_server._groups import owned_tasks
from robovoice.mcp_server.json_first import KEEPALIVE_S, JsonFirst, JsonFirstSessionManager
from robovoice.mcp_server.limits import BodyLimits
from robovoice.mcp_server.server import RobotToolServer
from robovoice.mcp_server.sse_deferral import DeferSse
from robovoice.mcp_server.tcp import listen_tcp

log = logging.getLogger(__name__)

MCP_PATH = "/mcp"
LOOPBACK_NAMES = frozenset({"localhost", "127.0.0.1", "::1"})
GRACEFUL_SHUTDOWN_S = 1


def is_loopback(host: str) -> bool:
    """Whether `host` (a name or an address) is this machine only."""
    name = host.strip("[]").lower()
    if name == "localhost":
        return True
    try:
        return ipaddress.ip_address(name).is_loopback
    except ValueError:
        return False


def check_bind(host: str, token: str | None) -> None:
    """Refuse a non-loopback bind without a token (`ConfigError`, with what to do)."""
    if token is None and not is_loopback(host):
        raise ConfigError(
            f"refusing to serve MCP over HTTP on {host}, which other machines can reach, without a bearer "
            "token: pass --token-file FILE (a file holding a long random secret), or bind 127.0.0.1"
        )


def read_token_file(path: Path) -> str:
    """The bearer token in `path` (surrounding whitespace removed); `ConfigError` if unusable."""
    token = read_secret_file(path, "token")
    if len(token) < 16 or any(c.isspace() for c in token):
        raise ConfigError(f"the token file {path} must hold one token of at least 16 characters, no spaces")
    return token


def _hostname(authority: str) -> str:
    """``host[:port]`` or ``[v6]:port`` → the lower-case host name."""
    if authority.startswith("["):
        return authority[1 : authority.find("]")].lower() if "]" in authority else ""
    return authority.rsplit(":", 1)[0].lower() if authority.count(":") == 1 else authority.lower()


class HttpGuard:
    """ASGI middleware: Host / Origin allow-list, then the bearer token (see module docstring).

    `any_host`: accept any ``Host`` (for a wildcard bind such as 0.0.0.0, where clients use
    whatever address reaches the machine; only allowed with a token, which a DNS-rebinding
    page cannot send). ``Origin`` is checked against `allowed_hosts` either way.
    """

    def __init__(self, app: ASGIApp, *, allowed_hosts: Iterable[str], token: str | None,
                 any_host: bool = False) -> None:
        if any_host and token is None:
            raise ConfigError("accepting any Host header needs a bearer token")
        self.app = app
        self.allowed_hosts = frozenset(h.strip("[]").lower() for h in allowed_hosts)
        self.any_host = any_host
        self._token = token.encode("utf-8") if token is not None else None

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = Headers(scope=scope)
        refusal = self._refusal(headers)
        if refusal is not None:
            await refusal(scope, receive, send)
            return
        await self.app(scope, receive, send)

    def _refusal(self, headers: Headers) -> PlainTextResponse | None:
        host = headers.get("host", "")
        if not self.any_host and _hostname(host) not in self.allowed_hosts:
            log.warning("refused a request for Host %r (DNS rebinding protection)", host[:100])
            return PlainTextResponse("Invalid Host header", status_code=421)
        origin = headers.get("origin")
        if origin is not None:
            parts = urlsplit(origin)
            if parts.scheme not in ("http", "https") or (parts.hostname or "") not in self.allowed_hosts:
                log.warning("refused a request from Origin %r (DNS rebinding protection)", origin[:100])
                return PlainTextResponse("Invalid Origin header", status_code=403)
        if self._token is not None:
            scheme, _, credentials = headers.get("authorization", "").partition(" ")
            given = credentials.strip().encode("utf-8")
            if scheme.lower() != "bearer" or not hmac.compare_digest(given, self._token):
                return PlainTextResponse("Unauthorized: send Authorization: Bearer <token>", status_code=401,
                                         headers={"WWW-Authenticate": 'Bearer realm="robovoice"'})
        return None


def is_wildcard(host: str) -> bool:
    return host.strip("[]") in ("0.0.0.0", "::", "")


def build_http_app(server: RobotToolServer, *, host: str = "127.0.0.1", token: str | None = None,
                   path: str = MCP_PATH, allowed_hosts: Iterable[str] = (),
                   keepalive_s: float = KEEPALIVE_S) -> ASGIApp:
    """The ASGI app: the SDK's streamable-HTTP session manager at `path`, behind `HttpGuard`;
    `JsonFirst` serves a 2026-07-28 request that cannot stream on the SDK's JSON path (SSE
    keep-alive pings after `keepalive_s` of silence), and `DeferSse` answers a 2025-session
    POST with JSON when its response is all it has to say.

    Allowed ``Host``/``Origin`` names: the loopback names, `host`, and `allowed_hosts`. A
    wildcard bind (0.0.0.0, ::) with a token and no `allowed_hosts` accepts any ``Host``.
    """
    manager = JsonFirstSessionManager(
        app=server.server,
        # The Host/Origin checks are HttpGuard's, on every path; the SDK's would duplicate them.
        security_settings=TransportSecuritySettings(enable_dns_rebinding_protection=False),
    )

    @asynccontextmanager
    async def lifespan(_: Starlette) -> AsyncIterator[None]:
        async with manager.run():
            yield

    app = Starlette(routes=[Route(path, endpoint=StreamableHTTPASGIApp(manager))], lifespan=lifespan)
    extra = frozenset(allowed_hosts)
    any_host = is_wildcard(host) and token is not None and not extra
    guarded = BodyLimits(JsonFirst(DeferSse(app), keepalive_s=keepalive_s))
    return HttpGuard(guarded, allowed_hosts=LOOPBACK_NAMES | {host} | extra, token=token, any_host=any_host)


@dataclass(frozen=True, slots=True)
class HttpEndpoint:
    host: str
    port: int
    path: str = MCP_PATH

    @property
    def url(self) -> str:
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"http://{host}:{self.port}{self.path}"


class _Uvicorn(uvicorn.Server):
    def __init__(self, config: uvicorn.Config) -> None:
        super().__init__(config)
        self.ready = asyncio.Event()

    async def startup(self, sockets: list[socket.socket] | None = None) -> None:
        await super().startup(sockets)
        self.ready.set()

    @contextlib.contextmanager
    def capture_signals(self) -> Iterator[None]:
        """Leave signals alone: the command line owns them (Ctrl-C cancels the whole robot)."""
        yield


@asynccontextmanager
async def http_server(
    server: RobotToolServer, *, host: str = "127.0.0.1", port: int = 0, token: str | None = None,
    allowed_hosts: Iterable[str] = (), **uvicorn_options: Any,
) -> AsyncIterator[HttpEndpoint]:
    """Serve `server` (already `running()`) over streamable HTTP until the block ends.

    ``port=0`` picks a free port; the yielded endpoint says which. Raises `ConfigError` for a
    non-loopback host without a token, or when the address cannot be bound.
    """
    check_bind(host, token)
    app = build_http_app(server, host=host, token=token, allowed_hosts=allowed_hosts)
    async with asgi_server(app, host=host, port=port, **uvicorn_options) as endpoint:
        log.info("MCP over streamable HTTP at %s%s", endpoint.url, " (bearer token required)" if token else "")
        yield endpoint


@asynccontextmanager
async def asgi_server(app: ASGIApp, *, host: str, port: int, **uvicorn_options: Any) -> AsyncIterator[HttpEndpoint]:
    """Run `app` under uvicorn on ``host:port`` (0: a free port) until the block ends.

    The listening socket is `listen_tcp`'s: every connection has ``TCP_NODELAY``, so a
    response that uvicorn writes as headers then body does not wait ~40 ms for the
    client's delayed ACK (Nagle).
    """
    sock = listen_tcp(host, port)
    endpoint = HttpEndpoint(host, sock.getsockname()[1])
    config = uvicorn.Config(app, log_config=None, lifespan="on", timeout_graceful_shutdown=GRACEFUL_SHUTDOWN_S,
                            **uvicorn_options)
    userver = _Uvicorn(config)
    try:
        async with owned_tasks() as group:
            serving = group.create_task(userver.serve(sockets=[sock]), name="mcp-http")
            ready = group.create_task(userver.ready.wait())
            await asyncio.wait({serving, ready}, return_when=asyncio.FIRST_COMPLETED)
            ready.cancel()
            if serving.done():
                raise ConfigError(f"the HTTP server for {endpoint.url} stopped during start-up")
            try:
                yield endpoint
            finally:
                userver.should_exit = True
    finally:
        sock.close()
