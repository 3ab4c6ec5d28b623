"""Payloads on the Zenoh wire: JSON text in UTF-8 (documented in docs/zenoh.md).

- RPC arguments (query payload) and results (reply payload): the JSON value itself.
- Errors: a Zenoh *error reply* whose payload is the JSON object
  ``{"error": code, "message": ..., "hint": ..., "details": {...}}`` (`RobotFailure.to_dict()`).
- Action feedback: ``{"progress": float, "total": float|null, "message": str, "data": {...}}``.
- NodeInfo: see `info_to_json`.
- Attachments (optional, JSON objects): ``{"stamp": <UNIX seconds>}`` on topic messages,
  ``{"feedback": <count>}`` on an action's result reply.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from robovoice.errors import RobotFailure
from robovoice.json_limits import json_depth_exceeds
from robovoice.middleware.base import JSON, Feedback, NodeInfo, RpcInfo
from robovoice.middleware.zenoh_keys import PROTOCOL_VERSION

ENCODING = "application/json"


def encode(value: JSON) -> bytes:
    """JSON text in UTF-8. Raises `TypeError`/`ValueError` for values JSON cannot carry."""
    return json.dumps(value, ensure_ascii=False, separators=(",", ":"), allow_nan=False).encode("utf-8")


MAX_DEPTH = 128


def decode(data: bytes) -> JSON:
    """Parse a JSON payload; an empty payload is ``null`` (raises `ValueError` otherwise, also for
    one nested deeper than `MAX_DEPTH`, which would end in a `RecursionError`)."""
    if not data:
        return None
    if json_depth_exceeds(data, MAX_DEPTH):
        raise ValueError(f"a payload nested deeper than {MAX_DEPTH} levels")
    return json.loads(data.decode("utf-8"))


def decode_object(data: bytes | None) -> dict[str, JSON]:
    """Parse an optional JSON object (attachments); anything else gives ``{}``."""
    if not data:
        return {}
    try:
        value = decode(data)
    except ValueError:
        return {}
    return value if isinstance(value, dict) else {}


# --- errors ----------------------------------------------------------------------------


def failure_to_bytes(failure: RobotFailure) -> bytes:
    try:
        return encode(failure.to_dict())
    except (TypeError, ValueError):  # details that JSON cannot carry: keep the rest
        body = failure.to_dict()
        body["details"] = {"unserialisable_details": repr(body["details"])}
        return encode(body)


def failure_from_bytes(data: bytes, where: str) -> RobotFailure:
    """The `RobotFailure` an error reply carries; a reply that is not one becomes `internal_error`."""
    try:
        body = decode(data)
    except ValueError:
        body = None
    if isinstance(body, dict) and isinstance(body.get("error"), str) and body["error"]:
        return RobotFailure.from_dict(body)
    text = data.decode("utf-8", errors="replace")[:500]
    return RobotFailure(f"{where} failed: {text}", code="internal_error", details={"where": where})


# --- feedback --------------------------------------------------------------------------


def feedback_to_bytes(feedback: Feedback) -> bytes:
    return encode({"progress": feedback.progress, "total": feedback.total,
                   "message": feedback.message, "data": dict(feedback.data)})


def feedback_from_bytes(data: bytes) -> Feedback:
    body = decode(data)
    if not isinstance(body, dict):
        raise ValueError("feedback must be a JSON object")
    total = body.get("total")
    data_field = body.get("data") or {}
    if not isinstance(data_field, dict):
        raise ValueError("feedback 'data' must be a JSON object")
    try:
        progress = float(body.get("progress", 0.0))
        total_value = None if total is None else float(total)
    except TypeError:  # a list or an object where a number belongs
        raise ValueError("feedback 'progress' and 'total' must be numbers") from None
    return Feedback(progress=progress, total=total_value, message=str(body.get("message") or ""), data=data_field)


# --- node info -------------------------------------------------------------------------


def info_to_json(info: NodeInfo) -> dict[str, JSON]:
    """The NodeInfo document a node serves on ``.../node/<node>/info``."""
    return {
        "protocol": PROTOCOL_VERSION,
        "name": info.name,
        "rpcs": [{"name": r.name, "kind": r.kind, "params": list(r.params), "description": r.description}
                 for r in info.rpcs],
        "topics": list(info.topics),
        "manifest": None if info.manifest is None else dict(info.manifest),
        "manifest_source": info.manifest_source,
    }


def _rpc_from_json(entry: Any) -> RpcInfo:
    if isinstance(entry, str):
        return RpcInfo(entry)
    if not isinstance(entry, dict) or not isinstance(entry.get("name"), str):
        raise ValueError(f"an RPC entry needs a string 'name': {entry!r}")
    kind = entry.get("kind", "rpc")
    if kind not in ("rpc", "action"):
        raise ValueError(f"RPC {entry['name']!r}: kind must be 'rpc' or 'action', not {kind!r}")
    params = entry.get("params") or []
    if not isinstance(params, list) or not all(isinstance(p, str) for p in params):
        raise ValueError(f"RPC {entry['name']!r}: params must be a list of strings")
    return RpcInfo(entry["name"], kind, tuple(params), str(entry.get("description") or ""))


def info_from_json(body: JSON, expected_name: str) -> NodeInfo:
    """Parse a NodeInfo document; raises `ValueError` saying what is wrong."""
    if not isinstance(body, dict):
        raise ValueError("the node info must be a JSON object")
    name = body.get("name", expected_name)
    if name != expected_name:
        raise ValueError(f"the node info names {name!r}, but its liveliness token is {expected_name!r}")
    rpcs = body.get("rpcs") or []
    topics = body.get("topics") or []
    manifest = body.get("manifest")
    if not isinstance(rpcs, list):
        raise ValueError("'rpcs' must be a list")
    if not isinstance(topics, list) or not all(isinstance(t, str) for t in topics):
        raise ValueError("'topics' must be a list of strings")
    if manifest is not None and not isinstance(manifest, Mapping):
        raise ValueError("'manifest' must be a JSON object or null")
    return NodeInfo(
        name=expected_name,
        rpcs=tuple(_rpc_from_json(entry) for entry in rpcs),
        topics=tuple(topics),
        manifest=manifest,
        manifest_source=str(body.get("manifest_source") or ""),
    )
