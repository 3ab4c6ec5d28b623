"""The small parts: the argument validator's error body, the audit log format, the HTTP guard."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from jsonschema.exceptions import SchemaError
from starlette.applications import Starlette
from starlette.responses import PlainTextResponse
from starlette.routing import Route
from starlette.testclient import TestClient

from robovoice.errors import ConfigError, InvalidArgumentsError
from robovoice.mcp_server import AuditLog, AuditRecord, read_token_file
from robovoice.mcp_server.http import HttpGuard, is_loopback
from robovoice.mcp_server.validation import ArgumentValidator

SCHEMA = {
    "type": "object",
    "properties": {"target": {"type": "string", "minLength": 1},
                   "speed": {"type": "number", "maximum": 1.0},
                   "stops": {"type": "array", "items": {"type": "string"}}},
    "required": ["target"],
    "additionalProperties": False,
}


def test_validator_reports_every_problem_with_paths_and_the_schema() -> None:
    validator = ArgumentValidator("navigate_to", SCHEMA)
    validator.validate({"target": "kitchen", "speed": 0.5, "stops": ["hallway"]})
    with pytest.raises(InvalidArgumentsError) as caught:
        validator.validate({"speed": 3, "stops": ["hallway", 7], "extra": True})
    body = caught.value.to_dict()
    assert body["error"] == "invalid_arguments"
    assert body["message"].startswith("invalid arguments for navigate_to: ")
    assert "schema" in body["hint"]
    paths = {e["path"] for e in body["details"]["errors"]}
    assert paths == {"$", "$.speed", "$.stops[1]"}  # missing target and the extra key are at the root
    messages = " ".join(e["message"] for e in body["details"]["errors"])
    assert "'target' is a required property" in messages and "'extra'" in messages
    assert body["details"]["schema"] == SCHEMA
    json.dumps(body)  # it is JSON


def test_validator_uses_draft_2020_12() -> None:
    schema = {"$schema": "https://json-schema.org/draft/2020-12/schema", "type": "object",
              "$defs": {"place": {"type": "string", "enum": ["kitchen"]}},
              "properties": {"target": {"$ref": "#/$defs/place"},
                             "xy": {"type": "array", "prefixItems": [{"type": "number"}, {"type": "number"}],
                                    "items": False}},
              "additionalProperties": False}
    validator = ArgumentValidator("t", schema)
    validator.validate({"target": "kitchen", "xy": [1, 2.5]})
    for bad in ({"target": "garage"}, {"xy": [1, "x"]}, {"xy": [1, 2, 3]}):
        with pytest.raises(InvalidArgumentsError):
            validator.validate(bad)
    with pytest.raises(SchemaError):  # the schema itself is checked against the 2020-12 metaschema
        ArgumentValidator("t", {"type": "object", "prefixItems": []})


def test_validator_remembers_valid_arguments_only_and_keeps_json_types_apart() -> None:
    validator = ArgumentValidator("t", {"type": "object", "properties": {"n": {"type": "integer"}}})
    walks = 0
    inner = validator._validator

    class Counting:  # counts the schema walks
        def iter_errors(self, instance: object) -> object:
            nonlocal walks
            walks += 1
            return inner.iter_errors(instance)

    validator._validator = Counting()  # a stand-in with the one method used
    validator.validate({"n": 1})
    validator.validate({"n": 1})
    assert walks == 1  # a repeat of known-valid arguments is recognised, not walked again
    for bad in ({"n": 1.5}, {"n": "1"}, {"n": 1.5}):
        with pytest.raises(InvalidArgumentsError):
            validator.validate(bad)
    assert walks == 4  # invalid arguments are never remembered
    with pytest.raises(InvalidArgumentsError):
        validator.validate({"n": True})  # JSON keeps true apart from the remembered 1
    for n in range(300):
        validator.validate({"n": n})
    assert len(validator._valid) == 256  # bounded: the oldest are forgotten


def _record(**changes: object) -> AuditRecord:
    fields: dict[str, object] = dict(
        started=1_795_000_000.25, session="abc", client="c/1", tool="get_camera_image", node="camera",
        rpc=None, arguments={}, outcome="ok", result={"image": {"mime_type": "image/jpeg"}, "data": "x" * 1000},
        error=None, duration_ms=1.23456)
    fields.update(changes)
    return AuditRecord(**fields)  # type: ignore[arg-type]  # a record's fields from a dict of mixed values


def test_audit_log_appends_one_json_line_per_call(tmp_path: Path) -> None:
    path = tmp_path / "deep" / "audit.jsonl"
    log = AuditLog(path)
    log.record(_record())
    log.record(_record(outcome="error", result=None, error={"error": "timeout", "message": "m", "hint": None,
                                                          "details": {}}))
    log.close()
    AuditLog(path).record(_record(tool="second_process"))  # a second writer appends, never truncates
    lines = [json.loads(line) for line in path.read_text().splitlines()]
    assert [r["tool"] for r in lines] == ["get_camera_image", "get_camera_image", "second_process"]
    first, failed, _ = lines
    assert first["time"] == "2026-11-18T11:06:40.250+00:00"
    assert first["duration_ms"] == 1.235 and first["session"] == "abc" and first["client"] == "c/1"
    assert first["result"]["data"] == "<1000 bytes base64>"  # images are not copied in
    assert "error" not in first and "result" not in failed
    assert failed["error"]["error"] == "timeout"
    assert os.stat(path).st_mode & 0o077 == 0  # private to the user


def test_an_unwritable_audit_log_is_a_config_error(tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(ConfigError, match="cannot open the audit log"):
        AuditLog(blocker / "audit.jsonl")


def test_disabled_audit_log_writes_nothing(tmp_path: Path) -> None:
    log = AuditLog(None)
    assert not log.enabled
    log.record(_record())
    assert list(tmp_path.iterdir()) == []


def _guarded(token: str | None = None, host: str = "127.0.0.1", any_host: bool = False) -> TestClient:
    async def ok(request: object) -> PlainTextResponse:
        return PlainTextResponse("ok")

    app = HttpGuard(Starlette(routes=[Route("/mcp", ok, methods=["GET", "POST"])]),
                    allowed_hosts={"localhost", "127.0.0.1", "::1", host}, token=token, any_host=any_host)
    return TestClient(app, base_url="http://127.0.0.1:8765")


def test_guard_checks_host_then_origin_then_token() -> None:
    client = _guarded(token="t" * 20)
    assert client.get("/mcp", headers={"Host": "evil.example.com"}).status_code == 421
    assert client.get("/mcp", headers={"Host": "127.0.0.1.evil.example.com:8765"}).status_code == 421
    assert client.get("/mcp", headers={"Host": "[::1]:8765", "Origin": "https://evil.example"}).status_code == 403
    assert client.get("/mcp", headers={"Origin": "file://"}).status_code == 403
    assert client.get("/mcp").status_code == 401
    assert client.get("/mcp", headers={"Authorization": "Bearer " + "t" * 19}).status_code == 401
    assert client.get("/mcp", headers={"Authorization": "bearer " + "t" * 20}).status_code == 200
    assert client.get("/other", headers={"Host": "evil.example.com"}).status_code == 421  # every path


def test_guard_allows_the_configured_host() -> None:
    client = _guarded(host="robot.local")
    assert client.get("/mcp", headers={"Host": "robot.local:8765", "Origin": "http://robot.local:8765"}).status_code \
        == 200
    assert client.get("/mcp", headers={"Host": "[::1]:8765", "Origin": "http://[::1]:8765"}).status_code == 200


def test_guard_for_a_wildcard_bind_accepts_any_host_but_needs_the_token() -> None:
    client = _guarded(token="t" * 20, host="0.0.0.0", any_host=True)
    auth = {"Authorization": "Bearer " + "t" * 20}
    assert client.get("/mcp", headers={**auth, "Host": "192.168.1.20:8765"}).status_code == 200
    assert client.get("/mcp", headers={"Host": "192.168.1.20:8765"}).status_code == 401
    assert client.get("/mcp", headers={**auth, "Origin": "http://evil.example"}).status_code == 403
    with pytest.raises(ConfigError, match="token"):
        HttpGuard(Starlette(), allowed_hosts=(), token=None, any_host=True)


def test_loopback_detection() -> None:
    assert all(is_loopback(h) for h in ("127.0.0.1", "127.1.2.3", "localhost", "::1", "[::1]", "LOCALHOST"))
    assert not any(is_loopback(h) for h in ("0.0.0.0", "::", "192.168.1.2", "robot.local", "localhost.evil"))


def test_token_file(tmp_path: Path) -> None:
    good = tmp_path / "token"
    good.write_text("  0123456789abcdef0123  \n")
    good.chmod(0o600)
    assert read_token_file(good) == "0123456789abcdef0123"
    short = tmp_path / "short"
    short.write_text("abc")
    with pytest.raises(ConfigError, match="at least 16"):
        read_token_file(short)
    with pytest.raises(ConfigError, match="cannot read"):
        read_token_file(tmp_path / "missing")
