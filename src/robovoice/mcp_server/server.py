"""`RobotToolServer`: the robot's manifest-declared functions as MCP tools.

The tool list is the union of the surfaces (manifest-declared tools and snapshots) of the
nodes present on the middleware. Presence events update the catalog at once (so the next
``tools/list`` is right), then a background task starts tracking new snapshot topics and
tells every connected client ``notifications/tools/list_changed``.

Only catalog entries are callable: a tool name resolves to a declared ``(node, rpc)`` or
to a snapshot topic, never to anything else, so an RPC no manifest declares (the sim
base's ``set_max_speed``) is unreachable under any name.

The SDK side is the low-level `mcp.server.lowlevel.Server` (a list that changes at run
time); `RobotToolServer.server` is what transports run.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import AsyncIterator, Mapping
from contextlib import asynccontextmanager
from typing import Any

import mcp_types as types
from jsonschema.exceptions import SchemaError
from mcp.server.context import ServerRequestContext
from mcp.server.lowlevel import NotificationOptions, Server
from mcp.server.models import InitializationOptions
from opentelemetry import trace

from robovoice import __version__
from robovoice.errors import RobovoiceError
from robovoice.manifest import (
    CatalogEntry,
    ManifestSet,
    NodeSurface,
    ToolCatalog,
    format_error,
    surface_for,
)
from robovoice.manifest.model import FOR_MODEL_META_KEY
from robovoice.manifest.voice import META_KEY as VOICE_META_KEY
from robovoice.mcp_server._groups import owned_tasks
from robovoice.mcp_server.audit import AuditLog
from robovoice.mcp_server.calls import ANONYMOUS, Caller, ProgressFn, ToolCalls
from robovoice.mcp_server.notify import ListChangedNotifier
from robovoice.mcp_server.validation import ArgumentValidator
from robovoice.middleware.base import JSON, Middleware, NodeJoined, NodeLeft, PresenceEvent
from robovoice.snapshot import SnapshotStore

log = logging.getLogger(__name__)

SERVER_NAME = "robovoice"
INSTRUCTIONS = (
    "Tools of a mobile home robot. Tool errors come back as JSON {error, message, hint, details}: "
    "read the hint before trying again. The tool list changes when parts of the robot go on or off line."
)


class _LowLevelServer(Server[Any]):
    """The SDK server, declaring ``tools.listChanged`` whoever builds the initialization options
    (stdio, the in-memory transport and the streamable-HTTP manager all call this)."""

    def create_initialization_options(
        self,
        notification_options: NotificationOptions | None = None,
        experimental_capabilities: dict[str, dict[str, Any]] | None = None,
        extensions: dict[str, dict[str, Any]] | None = None,
    ) -> InitializationOptions:
        return super().create_initialization_options(
            notification_options or NotificationOptions(tools_changed=True), experimental_capabilities, extensions
        )


def _tool(entry: CatalogEntry) -> types.Tool:
    """The MCP tool of a catalog entry; its manifest ``voice`` section (role, phrases) travels
    in ``_meta`` under ``robovoice/voice``, so a remote assistant gets it from ``tools/list``."""
    annotations = entry.annotations.model_dump(exclude_none=True)
    meta: dict[str, Any] = {VOICE_META_KEY: entry.voice.meta()} if entry.voice is not None else {}
    if not entry.for_model:  # for people and programs (a console's map), not the model
        meta[FOR_MODEL_META_KEY] = False
    return types.Tool(
        name=entry.name,
        description=entry.description,
        input_schema=entry.input_schema,
        annotations=types.ToolAnnotations.model_validate(annotations) if annotations else None,
        _meta=meta or None,
    )


def tracing_installed() -> bool:
    """Whether an OpenTelemetry tracer provider was installed (before this server was made)."""
    return not isinstance(trace.get_tracer_provider(), trace.ProxyTracerProvider)


def caller_of(ctx: ServerRequestContext[Any, Any]) -> Caller:
    """Session id (streamable HTTP) and client name/version, for the audit log."""
    session: str | None = None
    request = ctx.request
    headers = getattr(request, "headers", None)
    if headers is not None:
        session = headers.get("mcp-session-id")
    client: str | None = None
    params = ctx.session.client_params
    if params is not None:
        client = f"{params.client_info.name}/{params.client_info.version}"
    return Caller(session, client)


class RobotToolServer:
    """An MCP server whose tools come from the manifests of the nodes present.

    `manifests`: a folder's manifests overriding the nodes' own announcements (by node name).
    `audit`: where tool calls are logged (`AuditLog(None)` logs nothing).
    Use ``async with server.running():`` around serving: it follows presence.
    """

    def __init__(
        self,
        middleware: Middleware,
        *,
        manifests: ManifestSet | None = None,
        audit: AuditLog | None = None,
        snapshots: SnapshotStore | None = None,
        name: str = SERVER_NAME,
    ) -> None:
        self.middleware = middleware
        self.manifests = manifests
        self.audit = audit if audit is not None else AuditLog(None)
        self.snapshots = snapshots if snapshots is not None else SnapshotStore()
        self.catalog = ToolCatalog()
        self.notifier = ListChangedNotifier()
        self._calls = ToolCalls(middleware, self.snapshots, self.audit)
        self._tools: list[types.Tool] = []
        self._validators: dict[str, ArgumentValidator] = {}
        self._pending: asyncio.Queue[tuple[PresenceEvent, bool]] = asyncio.Queue()
        self._settled = asyncio.Event()
        self._settled.set()
        self._changed = asyncio.Event()
        self.server: Server[Any] = _LowLevelServer(
            name,
            version=__version__,
            instructions=INSTRUCTIONS,
            get_tool_input_schema=self.input_schema,
            on_list_tools=self._on_list_tools,
            on_call_tool=self._on_call_tool,
            on_subscriptions_listen=self.notifier.listen_handler,
        )
        self.server.add_notification_handler(
            "notifications/initialized", types.NotificationParams, self.notifier.on_initialized
        )
        if not tracing_installed():
            # The SDK wraps every request in an OpenTelemetry span by default; with no tracer installed
            # it records nothing but still costs ~20 µs a call. The SDK's documented opt-out.
            self.server.middleware = []

    # --- the tool surface --------------------------------------------------------------
    def tools(self) -> list[types.Tool]:
        """The MCP tool objects of ``tools/list`` now."""
        return list(self._tools)

    def input_schema(self, name: str) -> Mapping[str, Any] | None:
        entry = self.catalog.lookup(name)
        return entry.input_schema if entry is not None else None

    def _rebuild(self) -> None:
        tools: list[types.Tool] = []
        validators: dict[str, ArgumentValidator] = {}
        for entry in self.catalog.tools():
            try:
                validators[entry.name] = ArgumentValidator(entry.name, entry.input_schema)
            except SchemaError as exc:  # the manifest checks should have caught it: never serve it
                log.error("%s: %s: tool %s left out, its parameters are not a valid JSON Schema: %s",
                          entry.source, entry.path, entry.name, exc.message)
                continue
            tools.append(_tool(entry))
        self._tools = tools
        self._validators = validators

    # --- calls -------------------------------------------------------------------------
    async def call_tool(
        self,
        name: str,
        arguments: Mapping[str, JSON] | None = None,
        *,
        progress: ProgressFn | None = None,
        caller: Caller = ANONYMOUS,
    ) -> types.CallToolResult:
        """Call a tool as an MCP client would (the SDK handler goes through here)."""
        validator = self._validators.get(name)
        entry = self.catalog.lookup(name) if validator is not None else None
        return await self._calls.run(
            name, arguments or {}, entry, validator,
            available=lambda: sorted(self._validators), progress=progress, caller=caller,
        )

    async def _on_list_tools(
        self, ctx: ServerRequestContext[Any, Any], params: types.PaginatedRequestParams | None
    ) -> types.ListToolsResult:
        return types.ListToolsResult(tools=list(self._tools))

    async def _on_call_tool(
        self, ctx: ServerRequestContext[Any, Any], params: types.CallToolRequestParams
    ) -> types.CallToolResult:
        return await self.call_tool(
            params.name, params.arguments, progress=ctx.session.report_progress, caller=caller_of(ctx)
        )

    # --- presence ----------------------------------------------------------------------
    def _on_presence(self, event: PresenceEvent) -> None:
        """Middleware callback (on the event loop): update the catalog now, the rest later."""
        match event:
            case NodeJoined(info):
                surface = surface_for(info, self.manifests)
                for error in surface.errors:
                    log.warning("manifest problem, declaration not served: %s", format_error(error))
                changed = self.catalog.update(info.name, surface)
                for entry in surface.snapshots:
                    self.snapshots.publisher_back(entry.topic)
            case NodeLeft(name):
                old = self.catalog.surface(name)
                changed = self.catalog.update(name, None)
                for topic in _topics(old):
                    self.snapshots.publisher_gone(topic)
        if changed:
            self._rebuild()
            self._changed.set()
            self._changed = asyncio.Event()
        self._settled.clear()
        self._pending.put_nowait((event, changed))

    async def _follow_presence(self) -> None:
        while True:
            changed = False
            batch = [await self._pending.get()]
            while not self._pending.empty():  # a burst (a robot starting) gives one notification
                batch.append(self._pending.get_nowait())
            for event, event_changed in batch:
                changed = changed or event_changed
                if isinstance(event, NodeJoined):
                    await self._track(event.node.name)
            if changed:
                await self.notifier.tools_changed()
            if self._pending.empty():
                self._settled.set()

    async def _track(self, node: str) -> None:
        for topic in _topics(self.catalog.surface(node)):
            try:
                await self.snapshots.track(self.middleware, topic)
            except RobovoiceError as exc:  # the snapshot tool then answers "no message received yet"
                log.error("cannot subscribe to %r of node %r: %s", topic, node, exc)

    async def changed(self) -> None:
        """Return at the next change of the tool list."""
        await self._changed.wait()

    async def settled(self) -> None:
        """Wait until every presence event so far is fully handled (topics tracked, clients told)."""
        await self._settled.wait()

    @asynccontextmanager
    async def running(self) -> AsyncIterator[RobotToolServer]:
        """Follow the middleware's presence while serving. Nodes already present are in the
        catalog (and their snapshot topics tracked) when this yields."""
        try:
            async with owned_tasks() as group:
                follower = group.create_task(self._follow_presence(), name="mcp-presence")
                watch = await self.middleware.watch(self._on_presence)
                try:
                    await self.settled()
                    log.info("serving %d tools from nodes %s", len(self._tools), ", ".join(self.catalog.nodes()))
                    yield self
                finally:
                    watch.close()
                    self.notifier.close()
                    follower.cancel()
        finally:
            self.snapshots.close()


def _topics(surface: NodeSurface | None) -> list[str]:
    return [] if surface is None else [entry.topic for entry in surface.snapshots]
