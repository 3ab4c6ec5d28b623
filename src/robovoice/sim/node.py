"""What every sim node has in common: its shape, its manifest, argument checks.

A sim node is a plain object that says what it offers (`node_info`), how to serve it
(`rpc_handlers`, `action_handlers`) and what it does in the background while hosted
(`run`, e.g. publishing a topic; it runs until cancelled). `SimRobot` hosts nodes on any
`Middleware` and owns their background tasks.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from importlib import resources
from typing import Protocol

from robovoice.errors import InvalidArgumentsError
from robovoice.middleware.base import JSON, ActionHandler, NodeHost, NodeInfo, RpcHandler, RpcInfo


class SimNode(Protocol):
    name: str

    def node_info(self) -> NodeInfo: ...

    def rpc_handlers(self) -> Mapping[str, RpcHandler]: ...

    def action_handlers(self) -> Mapping[str, ActionHandler]: ...

    async def run(self, host: NodeHost) -> None:
        """Background work while hosted (publishing); runs until cancelled."""
        ...


def manifest_path(node: str) -> str:
    """Where the packaged manifest of sim node `node` lives."""
    return str(resources.files("robovoice.sim").joinpath("manifests", node, "mcp.json"))


def load_manifest(node: str) -> dict[str, JSON]:
    """The raw JSON of the packaged manifest of sim node `node`."""
    text = resources.files("robovoice.sim").joinpath("manifests", node, "mcp.json").read_text("utf-8")
    manifest = json.loads(text)
    if not isinstance(manifest, dict):
        raise TypeError(f"{manifest_path(node)}: a manifest is a JSON object")
    return manifest


def make_node_info(name: str, rpcs: tuple[RpcInfo, ...], topics: tuple[str, ...] = ()) -> NodeInfo:
    """The `NodeInfo` of a sim node, with its packaged manifest."""
    return NodeInfo(name, rpcs=rpcs, topics=topics, manifest=load_manifest(name),
                    manifest_source=manifest_path(name))


# --- argument checks (callers other than the MCP server validate nothing) ---------------


def check_args(args: Mapping[str, JSON], rpc: RpcInfo) -> None:
    """Reject arguments the RPC does not take."""
    unknown = sorted(set(args) - set(rpc.params))
    if unknown:
        raise InvalidArgumentsError(
            f"{rpc.name} takes {list(rpc.params) or 'no arguments'}, not {unknown}",
            details={"rpc": rpc.name, "unknown": unknown, "params": list(rpc.params)},
        )


def _missing(rpc: str, key: str, expected: str, args: Mapping[str, JSON]) -> InvalidArgumentsError:
    return InvalidArgumentsError(
        f"{rpc} needs {key!r} ({expected}), got {args.get(key)!r}",
        details={"rpc": rpc, "argument": key, "expected": expected},
    )


def str_arg(args: Mapping[str, JSON], rpc: str, key: str) -> str:
    value = args.get(key)
    if not isinstance(value, str) or not value.strip():
        raise _missing(rpc, key, "a non-empty string", args)
    return value


def bool_arg(args: Mapping[str, JSON], rpc: str, key: str) -> bool:
    value = args.get(key)
    if not isinstance(value, bool):
        raise _missing(rpc, key, "true or false", args)
    return value


def number_arg(args: Mapping[str, JSON], rpc: str, key: str) -> float:
    value = args.get(key)
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _missing(rpc, key, "a number", args)
    return float(value)
