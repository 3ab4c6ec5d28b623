"""TCP sockets without the Nagle / delayed-ACK stall, for robovoice's HTTP servers and clients.

An HTTP server that writes a response in two pieces (uvicorn: the headers, then the body)
on a socket where Nagle's algorithm is on holds the second piece back until the first is
acknowledged; the peer delays that acknowledgement by up to ~40 ms (Linux). Every call then
takes ~40 ms more than it should. asyncio turns Nagle off (``TCP_NODELAY``) on every TCP
transport it makes, but only for sockets whose ``proto`` is ``IPPROTO_TCP``; a listening
socket made by `socket.create_server` has ``proto`` 0, and so have the sockets it accepts,
so a server given such a listener (``loop.create_server(sock=...)``, uvicorn's
``serve(sockets=[...])``) keeps Nagle on. `listen_tcp` makes a listener whose accepted
sockets get ``TCP_NODELAY`` (asyncio sets it; Linux also inherits it from the listener).
`nodelay_transport` is an httpx2 transport whose connections set it explicitly.
"""

from __future__ import annotations

import socket
from typing import Any, Final

import httpx2

from robovoice.errors import ConfigError

NODELAY: Final = (socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
"""The socket option, in the ``(level, option, value)`` form httpx2's ``socket_options`` take."""


def listen_tcp(host: str, port: int) -> socket.socket:
    """A listening TCP socket on ``host:port`` (0: a free port) whose connections have
    ``TCP_NODELAY``; `ConfigError` when the address cannot be bound."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as socket.create_server does
        if family == socket.AF_INET6:
            sock.setsockopt(socket.IPPROTO_IPV6, socket.IPV6_V6ONLY, 1)
        sock.setsockopt(*NODELAY)
        sock.bind((host.strip("[]"), port))
        sock.listen()
    except OSError as exc:
        sock.close()
        raise ConfigError(f"cannot listen on {host}:{port}: {exc.strerror or exc}") from None
    return sock


def nodelay_transport(**options: Any) -> httpx2.AsyncHTTPTransport:
    """An httpx2 transport (``httpx2.AsyncClient(transport=...)``) whose TCP connections set
    ``TCP_NODELAY``; `options` go to `httpx2.AsyncHTTPTransport`."""
    return httpx2.AsyncHTTPTransport(socket_options=[NODELAY], **options)
