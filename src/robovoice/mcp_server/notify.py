"""`notifications/tools/list_changed` to every connected client, in both protocol eras.

- Handshake era (2025-xx, what stdio/HTTP clients with ``initialize`` speak): every
  connection that sent ``notifications/initialized`` is registered for as long as it
  lives, and gets the notification on its standalone channel (the stdio pipe, or the
  streamable-HTTP GET stream).
- 2026-07-28 era: change notifications only travel on ``subscriptions/listen`` streams; we
  publish on the SDK's subscription bus and its `ListenHandler` serves those streams.

How a handshake connection is registered: the handler of ``notifications/initialized``
adds the connection's `ServerSession` and then simply waits. The SDK runs notification
handlers in the connection's own task group and cancels them when the connection ends,
so the ``finally`` removes the session exactly when the connection goes away, with no
task of ours to leak and no private SDK attribute to read.
"""

from __future__ import annotations

import logging
from typing import Any

import anyio
import mcp_types as types
from mcp.server.context import ServerRequestContext
from mcp.server.session import ServerSession
from mcp.server.subscriptions import InMemorySubscriptionBus, ListenHandler, ToolsListChanged

log = logging.getLogger(__name__)

SEND_TIMEOUT_S = 2.0
"""A client that does not take a notification within this time is skipped (not waited on)."""


class ListChangedNotifier:
    """Knows the live sessions and tells them all that the tool list changed."""

    def __init__(self) -> None:
        self._sessions: dict[int, ServerSession] = {}
        self._next = 0
        self.bus = InMemorySubscriptionBus()
        self.listen_handler = ListenHandler(self.bus)

    @property
    def session_count(self) -> int:
        """Handshake-era connections registered now."""
        return len(self._sessions)

    async def on_initialized(self, ctx: ServerRequestContext[Any, Any], params: types.NotificationParams) -> None:
        """Handler of ``notifications/initialized``: registered until the connection ends."""
        self._next += 1
        key = self._next
        self._sessions[key] = ctx.session
        log.debug("session %d registered for list_changed (%d live)", key, len(self._sessions))
        try:
            await anyio.sleep_forever()
        finally:
            self._sessions.pop(key, None)
            log.debug("session %d gone (%d live)", key, len(self._sessions))

    async def tools_changed(self) -> None:
        """Notify every handshake-era session and every 2026-era listen stream."""
        sessions = list(self._sessions.values())
        async with anyio.create_task_group() as tg:
            for session in sessions:
                tg.start_soon(self._send, session)
        await self.bus.publish(ToolsListChanged())
        log.info("tools/list_changed sent to %d session(s) and the listen streams", len(sessions))

    async def _send(self, session: ServerSession) -> None:
        with anyio.move_on_after(SEND_TIMEOUT_S) as scope:
            try:
                await session.send_tool_list_changed()
            except (anyio.BrokenResourceError, anyio.ClosedResourceError):
                log.debug("list_changed not delivered: the session's stream is closed")
        if scope.cancelled_caught:
            log.warning("list_changed not delivered within %g s to a session", SEND_TIMEOUT_S)

    def close(self) -> None:
        """End the 2026-era listen streams gracefully (on shutdown)."""
        self.listen_handler.close()
