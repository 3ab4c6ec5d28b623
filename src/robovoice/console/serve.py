"""Serving the console: the security rules of the MCP HTTP server (127.0.0.1 by default, no
non-loopback address without a bearer token), uvicorn on `asgi_server`'s socket."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterable
from contextlib import asynccontextmanager

from robovoice.console.app import build_console_app
from robovoice.console.service import Console
from robovoice.errors import ConfigError
from robovoice.mcp_server.http import HttpEndpoint, asgi_server, is_loopback


def check_console_bind(host: str, token: str | None) -> None:
    """Refuse a non-loopback bind without a token (`ConfigError`, with what to do)."""
    if token is None and not is_loopback(host):
        raise ConfigError(
            f"refusing to serve the console on {host}, which other machines can reach, without a bearer token: "
            "pass --token-file FILE (a file holding a long random secret), or bind 127.0.0.1"
        )


@asynccontextmanager
async def console_server(console: Console, *, host: str = "127.0.0.1", port: int = 0, token: str | None = None,
                         allowed_hosts: Iterable[str] = ()) -> AsyncIterator[HttpEndpoint]:
    """Serve `console` until the block ends; the endpoint's ``url`` is the page (``path`` "/")."""
    check_console_bind(host, token)
    app = build_console_app(console, host=host, token=token, allowed_hosts=allowed_hosts)
    async with asgi_server(app, host=host, port=port) as endpoint:
        yield HttpEndpoint(endpoint.host, endpoint.port, "/")
