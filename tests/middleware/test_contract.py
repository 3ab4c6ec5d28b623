"""The Middleware contract, run against every adapter (memory, and Zenoh on loopback).

For Zenoh the nodes and the client live in two sessions joined over TCP on a fresh
loopback port (multicast scouting off), so every call crosses the wire.
"""

from __future__ import annotations

import asyncio
import socket
from collections.abc import AsyncIterator
from dataclasses import dataclass

import pytest

from robovoice.errors import CallTimeoutError, NodeUnavailableError, RobotFailure
from robovoice.middleware.base import (
    JSON,
    ActionHandler,
    Feedback,
    FeedbackSender,
    Message,
    Middleware,
    NodeHost,
    NodeInfo,
    NodeJoined,
    NodeLeft,
    PresenceEvent,
    RpcHandler,
    RpcInfo,
)
from robovoice.middleware.memory import MemoryMiddleware

from ..waiting import until

MANIFEST = {"node": "echo", "tools": [{"name": "say", "rpc": "echo"}]}
INFO = NodeInfo("echo", rpcs=(RpcInfo("echo", params=("text",)), RpcInfo("count", "action", ("n",))),
                topics=("battery",), manifest=MANIFEST, manifest_source="tests/echo/mcp.json")
BOUND_S = 5.0


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@dataclass
class Pair:
    """`client` calls, `nodes` hosts; the same object for in-process adapters."""

    client: Middleware
    nodes: Middleware

    async def host(self, info: NodeInfo, rpcs: dict[str, RpcHandler],
                   actions: dict[str, ActionHandler]) -> NodeHost:
        host = await self.nodes.host(info, rpcs, actions)
        await until(lambda: info.name in self.client.nodes())
        return host


@pytest.fixture(params=["memory", "zenoh"])
async def pair(request: pytest.FixtureRequest) -> AsyncIterator[Pair]:
    if request.param == "memory":
        bus = MemoryMiddleware()
        await bus.start()
        yield Pair(bus, bus)
        await bus.close()
        return
    from robovoice.middleware.zenoh import ZenohMiddleware

    port = free_port()
    nodes = ZenohMiddleware.from_uri(f"zenoh://?listen=tcp/127.0.0.1:{port}&robot=contract")
    client = ZenohMiddleware.from_uri(f"zenoh://?connect=tcp/127.0.0.1:{port}&robot=contract&must_connect=1")
    await nodes.start()
    try:
        await client.start()
        try:
            yield Pair(client, nodes)
        finally:
            await client.close()
    finally:
        await nodes.close()


async def _echo(args: dict[str, JSON]) -> JSON:
    text = args.get("text")
    if text == "fail":
        raise RobotFailure("asked to fail", code="unknown_target", hint="h", details={"k": 1})
    if text == "bug":
        raise ValueError("oops")
    if text == "slow":
        await asyncio.Event().wait()
    return {"echo": text, "args": args}


async def _count(args: dict[str, JSON], feedback: FeedbackSender) -> JSON:
    n = args["n"]
    assert isinstance(n, int)
    for i in range(n):
        await feedback(Feedback(progress=i + 1, total=n, message=f"step {i + 1}", data={"i": i}))
    if args.get("block"):
        await asyncio.Event().wait()
    return n


@pytest.fixture
async def echo(pair: Pair) -> NodeHost:
    return await pair.host(INFO, {"echo": _echo}, {"count": _count})


async def test_call_round_trip(pair: Pair, echo: NodeHost) -> None:
    args: dict[str, JSON] = {"text": "hi", "nested": {"list": [1, 2.5, None, True, "ü"]}}
    result = await pair.client.call("echo", "echo", args, timeout=2)
    assert result == {"echo": "hi", "args": args}
    assert result["args"] is not args  # a copy, as over a network


async def test_failures_pass_through_with_codes(pair: Pair, echo: NodeHost) -> None:
    with pytest.raises(RobotFailure) as err:
        await pair.client.call("echo", "echo", {"text": "fail"}, timeout=2)
    assert err.value.to_dict() == {"error": "unknown_target", "message": "asked to fail", "hint": "h",
                                   "details": {"k": 1}}
    assert type(err.value) is RobotFailure


async def test_node_bug_becomes_internal_error(pair: Pair, echo: NodeHost) -> None:
    with pytest.raises(RobotFailure) as err:
        await pair.client.call("echo", "echo", {"text": "bug"}, timeout=2)
    assert err.value.code == "internal_error"
    assert "oops" in err.value.message


async def test_timeout(pair: Pair, echo: NodeHost) -> None:
    loop = asyncio.get_running_loop()
    start = loop.time()
    with pytest.raises(CallTimeoutError) as err:
        await pair.client.call("echo", "echo", {"text": "slow"}, timeout=0.2)
    assert err.value.code == "timeout"
    assert loop.time() - start < 1.5


async def test_missing_node_and_unknown_rpc(pair: Pair, echo: NodeHost) -> None:
    with pytest.raises(NodeUnavailableError) as err:
        await pair.client.call("ghost", "echo", {}, timeout=2)
    assert err.value.code == "node_unavailable"
    with pytest.raises(RobotFailure) as failure:
        await pair.client.call("echo", "nope", {}, timeout=2)
    assert failure.value.code == "unknown_rpc"
    with pytest.raises(RobotFailure) as failure:  # an action is not an RPC
        await pair.client.call("echo", "count", {"n": 1}, timeout=2)
    assert failure.value.code == "unknown_rpc"

    async def noop(feedback: Feedback) -> None: ...

    with pytest.raises(RobotFailure) as failure:  # nor the other way round
        await pair.client.run_action("echo", "echo", {"text": "x"}, on_feedback=noop, timeout=2)
    assert failure.value.code == "unknown_rpc"


async def test_action_feedback_then_result(pair: Pair, echo: NodeHost) -> None:
    seen: list[Feedback] = []

    async def on_feedback(feedback: Feedback) -> None:
        seen.append(feedback)

    result = await pair.client.run_action("echo", "count", {"n": 3}, on_feedback=on_feedback, timeout=2)
    assert result == 3
    assert [(f.progress, f.total, f.message, dict(f.data)) for f in seen] == [
        (1, 3, "step 1", {"i": 0}), (2, 3, "step 2", {"i": 1}), (3, 3, "step 3", {"i": 2})]


async def test_cancelling_the_caller_cancels_the_action_on_the_node(pair: Pair) -> None:
    started = asyncio.Event()
    cancelled = asyncio.Event()

    async def drive(args: dict[str, JSON], feedback: FeedbackSender) -> JSON:
        started.set()
        try:
            await asyncio.Event().wait()
        except asyncio.CancelledError:
            cancelled.set()
            raise
        return None

    await pair.host(NodeInfo("nav", rpcs=(RpcInfo("drive", "action"),)), {}, {"drive": drive})

    async def noop(feedback: Feedback) -> None: ...

    task = asyncio.create_task(pair.client.run_action("nav", "drive", {}, on_feedback=noop, timeout=10))
    await asyncio.wait_for(started.wait(), BOUND_S)
    task.cancel()
    await asyncio.wait_for(cancelled.wait(), BOUND_S)
    with pytest.raises(asyncio.CancelledError):
        await task


async def test_action_timeout_cancels_it_on_the_node(pair: Pair) -> None:
    cancelled = asyncio.Event()

    async def drive(args: dict[str, JSON], feedback: FeedbackSender) -> JSON:
        try:
            await asyncio.Event().wait()
        except asyncio.CancelledError:
            cancelled.set()
            raise
        return None

    await pair.host(NodeInfo("nav", rpcs=(RpcInfo("drive", "action"),)), {}, {"drive": drive})

    async def noop(feedback: Feedback) -> None: ...

    with pytest.raises(CallTimeoutError):
        await pair.client.run_action("nav", "drive", {}, on_feedback=noop, timeout=0.2)
    await asyncio.wait_for(cancelled.wait(), BOUND_S)


async def test_node_leaving_mid_action(pair: Pair, echo: NodeHost) -> None:
    seen: list[Feedback] = []

    async def on_feedback(feedback: Feedback) -> None:
        seen.append(feedback)

    task = asyncio.create_task(pair.client.run_action(
        "echo", "count", {"n": 1, "block": True}, on_feedback=on_feedback, timeout=10))
    await until(lambda: len(seen) == 1)
    await echo.leave()
    with pytest.raises(NodeUnavailableError):
        await asyncio.wait_for(task, BOUND_S)
    await until(lambda: "echo" not in pair.client.nodes())
    with pytest.raises(NodeUnavailableError):
        await pair.client.call("echo", "echo", {"text": "hi"}, timeout=2)


async def test_topics(pair: Pair) -> None:
    got: list[Message] = []
    other: list[Message] = []
    sub = await pair.client.subscribe("battery", got.append)
    await pair.client.subscribe("pose", other.append)
    host = await pair.host(NodeInfo("base", topics=("battery", "pose")), {}, {})
    # Zenoh subscriptions take a moment to reach the publisher: publish until one arrives
    async with asyncio.timeout(BOUND_S):
        while not got:
            host.publish("battery", {"percent": 80}, stamp=1.0)
            await asyncio.sleep(0.01)
    assert got[0] == Message("battery", {"percent": 80}, 1.0)
    assert other == []
    before = len(got)
    sub.close()
    host.publish("battery", {"percent": 79})
    host.publish("pose", {"x": 1.5})
    await until(lambda: len(other) == 1)
    assert other[0].value == {"x": 1.5} and other[0].stamp > 1.0
    assert len(got) == before


async def test_presence(pair: Pair, echo: NodeHost) -> None:
    events: list[PresenceEvent] = []
    watch = await pair.client.watch(events.append)
    assert events == [NodeJoined(INFO)]  # present nodes are reported as joined, with the manifest
    host = await pair.host(NodeInfo("base", topics=("battery",)), {}, {})
    await until(lambda: len(events) == 2)
    assert events[1] == NodeJoined(NodeInfo("base", topics=("battery",)))
    await host.leave()
    await until(lambda: len(events) == 3)
    assert events[2] == NodeLeft("base")
    watch.close()
    assert set(pair.client.nodes()) == {"echo"}
    assert pair.client.nodes()["echo"].manifest == MANIFEST
