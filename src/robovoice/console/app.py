"""The console's HTTP surface: the page, the API and two WebSockets, behind the MCP HTTP
server's guard (`robovoice.mcp_server.http.HttpGuard`: Host/Origin allow-list, bearer token).

    GET  /                  the page (static files under /static/)
    GET  /api/state         the robot's state, recent turns, the voice's status
    POST /api/say           {"text": ...} -> one typed turn and its events
    GET  /api/tools         every tool, with its JSON Schema and annotations
    POST /api/call          {"name": ..., "arguments": {...}} -> the tool's result
    GET  /api/audit         ?tool=NAME&errors=true|false&limit=N, newest first
    GET  /api/answers/N.wav the robot's spoken answer of voice turn N (typed-N.wav: typed turn N)
    WS   /ws/events         live: conversation events, robot state, audit records
    WS   /ws/audio          up: 16 kHz mono int16 PCM and {"type": "ptt"}; down: the robot's voice

`ConsoleGuard` extends the guard to WebSockets (refused with the same status codes before
the handshake completes) and lets a browser carry the token as a cookie, set by ``/login``
(SameSite=Strict, HttpOnly), since a page cannot add an Authorization header to its own
navigation or to a WebSocket.
"""

from __future__ import annotations

import asyncio
import hmac
import json
from collections.abc import Iterable
from http.cookies import SimpleCookie
from importlib import resources
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.datastructures import Headers
from starlette.requests import Request
from starlette.responses import FileResponse, HTMLResponse, JSONResponse, RedirectResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.types import Receive, Scope, Send
from starlette.websockets import WebSocket, WebSocketDisconnect

from robovoice.console.service import Console
from robovoice.mcp_server.http import LOOPBACK_NAMES, HttpGuard, is_wildcard
from robovoice.mcp_server.limits import BodyLimits

COOKIE = "robovoice_console_token"
LOGIN_PATH = "/login"
MAX_BODY = 1 << 20

STATIC = Path(str(resources.files("robovoice.console").joinpath("static")))


class BadRequest(Exception):
    pass


class ConsoleGuard(HttpGuard):
    """`HttpGuard` for HTTP and WebSocket scopes; the token may also come as the login cookie.
    ``/login`` itself passes with Host/Origin checks only."""

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        headers = Headers(scope=scope)
        if self._token is not None and "authorization" not in headers:
            given = self._token.decode() if scope.get("path") == LOGIN_PATH else _cookie(headers, COOKIE)
            if given is not None:
                headers = Headers(raw=[*scope["headers"], (b"authorization", f"Bearer {given}".encode())])
        refusal = self._refusal(headers)
        if refusal is None:
            await self.app(scope, receive, send)
        elif scope["type"] == "http":
            await refusal(scope, receive, send)
        else:
            await _refuse_websocket(scope, send, refusal)

    def token_matches(self, given: str) -> bool:
        return self._token is not None and hmac.compare_digest(given.encode("utf-8"), self._token)


def _cookie(headers: Headers, name: str) -> str | None:
    jar: SimpleCookie = SimpleCookie()
    try:
        jar.load(headers.get("cookie", ""))
    except Exception:  # a malformed cookie header is no token
        return None
    morsel = jar.get(name)
    return morsel.value if morsel is not None else None


async def _refuse_websocket(scope: Scope, send: Send, refusal: Response) -> None:
    """Answer a WebSocket handshake with `refusal`'s status (ASGI's denial response where the
    server has it, else a plain close, which servers turn into 403)."""
    if "websocket.http.response" in scope.get("extensions", {}):
        await send({"type": "websocket.http.response.start", "status": refusal.status_code,
                    "headers": [(k, v) for k, v in refusal.raw_headers if k != b"content-length"]})
        await send({"type": "websocket.http.response.body", "body": refusal.body})
    else:
        await send({"type": "websocket.close", "code": 1008})


async def _json_body(request: Request) -> dict[str, Any]:
    raw = await request.body()
    if len(raw) > MAX_BODY:
        raise BadRequest(f"the body is larger than {MAX_BODY} bytes")
    try:
        body = json.loads(raw or b"null")
    except ValueError as exc:
        raise BadRequest(f"the body is not JSON: {exc}") from None
    if not isinstance(body, dict):
        raise BadRequest("the body must be a JSON object")
    return body


def _bad(message: str) -> JSONResponse:
    return JSONResponse({"error": "bad_request", "message": message}, status_code=400)


def build_console_app(console: Console, *, host: str = "127.0.0.1", token: str | None = None,
                      allowed_hosts: Iterable[str] = ()) -> ConsoleGuard:
    """The console's ASGI app behind `ConsoleGuard` (same rules as `build_http_app`)."""

    async def page(_: Request) -> Response:
        return FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-store"})

    async def state(request: Request) -> Response:
        try:
            turns = int(request.query_params.get("turns", "20"))
        except ValueError:
            return _bad("turns must be a whole number")
        return JSONResponse(console.state(max(0, min(turns, 50))))

    async def say(request: Request) -> Response:
        try:
            body = await _json_body(request)
        except BadRequest as exc:
            return _bad(str(exc))
        text = body.get("text")
        if not isinstance(text, str) or not text.strip():
            return _bad('send {"text": "what to say to the robot"}')
        return JSONResponse(await console.say(text.strip()))

    async def tools(_: Request) -> Response:
        return JSONResponse({"tools": await console.tool_list()})

    async def call(request: Request) -> Response:
        try:
            body = await _json_body(request)
        except BadRequest as exc:
            return _bad(str(exc))
        name, arguments = body.get("name"), body.get("arguments", {})
        if not isinstance(name, str) or not name:
            return _bad('send {"name": "tool_name", "arguments": {...}}')
        if not isinstance(arguments, dict):
            return _bad("arguments must be a JSON object")
        return JSONResponse(await console.call(name, arguments))

    async def audit(request: Request) -> Response:
        params = request.query_params
        errors_text = params.get("errors")
        if errors_text not in (None, "", "true", "false"):
            return _bad("errors must be true or false")
        try:
            limit = max(1, min(int(params.get("limit", "100")), 1000))
        except ValueError:
            return _bad("limit must be a whole number")
        errors = None if not errors_text else errors_text == "true"
        return JSONResponse({"records": console.audit.query(tool=params.get("tool") or None, errors=errors,
                                                            limit=limit)})

    async def answer(request: Request) -> Response:
        turn = request.path_params["turn"]
        typed = request.url.path.startswith("/api/answers/typed-")
        path = console.voice.answer_path(turn, typed=typed) if console.voice is not None else None
        if path is None or not path.is_file():
            return JSONResponse({"error": "not_found", "message": f"no spoken answer for voice turn {turn}"},
                                status_code=404)
        return FileResponse(path, media_type="audio/wav")

    async def login(request: Request) -> Response:
        if request.method == "GET":
            return HTMLResponse(_LOGIN_FORM)
        form = await request.form()
        given = form.get("token")
        if not isinstance(given, str) or not guard.token_matches(given.strip()):
            return HTMLResponse(_LOGIN_FORM.replace("<!--msg-->", "<p>Wrong token.</p>"), status_code=401)
        response = RedirectResponse("/", status_code=303)
        response.set_cookie(COOKIE, given.strip(), httponly=True, samesite="strict")
        return response

    async def events(ws: WebSocket) -> None:
        await ws.accept()
        with console.hub.subscribe() as queue:
            await ws.send_json({"type": "hello", **console.state()})

            async def pump() -> None:
                while True:
                    await ws.send_json(await queue.get())

            sender = asyncio.create_task(pump(), name="console-ws-events")
            try:
                while True:
                    message = await ws.receive()
                    if message["type"] == "websocket.disconnect":
                        break
            finally:
                sender.cancel()
                await asyncio.gather(sender, return_exceptions=True)

    async def audio(ws: WebSocket) -> None:
        voice = console.voice
        await ws.accept()
        if voice is None:
            await ws.close(code=1008, reason="the console runs without voice (--no-voice)")
            return
        voice.connect(ws, ws.send_bytes)
        try:
            while True:
                message = await ws.receive()
                if message["type"] == "websocket.disconnect":
                    break
                if not voice.holds(ws):
                    continue  # another page took the microphone over
                data = message.get("bytes")
                if data:
                    voice.mic.push(data)
                elif message.get("text"):
                    try:
                        control = json.loads(message["text"])
                    except ValueError:
                        continue
                    if isinstance(control, dict) and control.get("type") == "ptt":
                        voice.push_to_talk()
        except WebSocketDisconnect:
            pass
        finally:
            voice.disconnect(ws)

    routes = [
        Route("/", page),
        Route("/api/state", state),
        Route("/api/say", say, methods=["POST"]),
        Route("/api/tools", tools),
        Route("/api/call", call, methods=["POST"]),
        Route("/api/audit", audit),
        Route("/api/answers/{turn:int}.wav", answer),
        Route("/api/answers/typed-{turn:int}.wav", answer),
        Route(LOGIN_PATH, login, methods=["GET", "POST"]),
        WebSocketRoute("/ws/events", events),
        WebSocketRoute("/ws/audio", audio),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    app = BodyLimits(Starlette(routes=routes), jsonrpc=False)  # 413 / 400 before a body is buffered or parsed
    extra = frozenset(allowed_hosts)
    any_host = is_wildcard(host) and token is not None and not extra
    guard = ConsoleGuard(app, allowed_hosts=LOOPBACK_NAMES | {host} | extra, token=token, any_host=any_host)
    return guard


_LOGIN_FORM = """<!doctype html><html><head><meta charset="utf-8"><title>robovoice console: sign in</title></head>
<body style="font-family:sans-serif;max-width:30em;margin:4em auto">
<h1>robovoice console</h1><!--msg-->
<form method="post" action="/login"><label>Bearer token <input type="password" name="token" autofocus></label>
<button type="submit">Open the console</button></form></body></html>"""
