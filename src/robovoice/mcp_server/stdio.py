"""The stdio transport: one client on this process's stdin/stdout until stdin closes.

Nothing else may write to stdout while it runs: logging goes to stderr (the CLI sets that up).
"""

from __future__ import annotations

import logging

from mcp.server.stdio import stdio_server

from robovoice.mcp_server.server import RobotToolServer

log = logging.getLogger(__name__)


async def serve_stdio(server: RobotToolServer) -> None:
    """Serve `server` (already `running()`) over stdio until the client closes stdin."""
    async with stdio_server() as (read_stream, write_stream):
        log.info("MCP over stdio")
        await server.server.run(read_stream, write_stream, server.server.create_initialization_options())
