"""The MCP server built from manifests: tools from the nodes present, dispatched to the middleware.

- `RobotToolServer` (server.py): the tool surface and the SDK low-level server;
- transports: `serve_stdio` (stdio.py), `http_server` (http.py, streamable HTTP behind a guard);
- `open_robot_side` (runtime.py): middleware + sim + server as one (`RobotSide`), for a robot
  address served in this process; `open_embedded_client` (embedded.py): an SDK client
  connected to it in memory;
- `AuditLog` (audit.py), argument validation (validation.py), result shapes (results.py).
See docs/mcp-server.md.
"""

from __future__ import annotations

from robovoice.mcp_server.audit import AuditLog, AuditRecord, default_audit_path
from robovoice.mcp_server.calls import Caller
from robovoice.mcp_server.embedded import open_embedded_client
from robovoice.mcp_server.http import HttpEndpoint, build_http_app, check_bind, http_server, read_token_file
from robovoice.mcp_server.runtime import RobotSide, open_robot_side, wait_for_snapshots, wait_for_tools
from robovoice.mcp_server.server import RobotToolServer
from robovoice.mcp_server.stdio import serve_stdio

__all__ = [
    "AuditLog",
    "AuditRecord",
    "Caller",
    "HttpEndpoint",
    "RobotSide",
    "RobotToolServer",
    "build_http_app",
    "check_bind",
    "default_audit_path",
    "http_server",
    "open_embedded_client",
    "open_robot_side",
    "read_token_file",
    "serve_stdio",
    "wait_for_snapshots",
    "wait_for_tools",
]
