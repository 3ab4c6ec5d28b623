"""The memory middleware honours the Middleware contract."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from robovoice.errors import CallTimeoutError, NodeUnavailableError, RobotFailure, UnsupportedURIError
from robovoice.middleware import open_middleware
from robovoice.middleware.base import Feedback, FeedbackSender, Message, NodeInfo, NodeJoined, NodeLeft, RpcInfo
from robovoice.middleware.memory import MemoryMiddleware

INFO = NodeInfo("echo", rpcs=(RpcInfo("echo", params=("text",)), RpcInfo("count", "action", ("n",))))


async def _echo(args: dict[str, Any]) -> dict[str, Any]:
    if args.get("text") == "fail":
        raise RobotFailure("asked to fail", code="unknown_target", hint="h", details={"k": 1})
    if args.get("text") == "bug":
        raise ValueError("oops")
    if args.get("text") == "slow":
        await asyncio.Event().wait()
    return {"echo": args["text"]}


async def _count(args: dict[str, Any], feedback: FeedbackSender) -> int:
    for i in range(args["n"]):
        await feedback(Feedback(progress=i + 1, total=args["n"]))
        await asyncio.sleep(0)
    if args.get("block"):
        await asyncio.Event().wait()
    return int(args["n"])


@pytest.fixture
async def bus() -> MemoryMiddleware:
    bus = MemoryMiddleware()
    await bus.start()
    await bus.host(INFO, {"echo": _echo}, {"count": _count})
    return bus


async def test_call_roundtrip_copies_values(bus: MemoryMiddleware) -> None:
    args = {"text": "hi"}
    assert await bus.call("echo", "echo", args, timeout=1) == {"echo": "hi"}


async def test_robot_failure_passes_through_and_bugs_become_internal_error(bus: MemoryMiddleware) -> None:
    with pytest.raises(RobotFailure) as err:
        await bus.call("echo", "echo", {"text": "fail"}, timeout=1)
    assert err.value.to_dict() == {"error": "unknown_target", "message": "asked to fail", "hint": "h",
                                   "details": {"k": 1}}
    with pytest.raises(RobotFailure) as err:
        await bus.call("echo", "echo", {"text": "bug"}, timeout=1)
    assert err.value.code == "internal_error"


async def test_timeout_and_missing_node(bus: MemoryMiddleware) -> None:
    with pytest.raises(CallTimeoutError):
        await bus.call("echo", "echo", {"text": "slow"}, timeout=0.05)
    with pytest.raises(NodeUnavailableError):
        await bus.call("ghost", "echo", {}, timeout=1)


async def test_action_feedback_and_node_leaving_mid_action(bus: MemoryMiddleware) -> None:
    seen: list[Feedback] = []

    async def on_feedback(fb: Feedback) -> None:
        seen.append(fb)

    assert await bus.run_action("echo", "count", {"n": 3}, on_feedback=on_feedback, timeout=1) == 3
    assert [f.progress for f in seen] == [1, 2, 3]

    task = asyncio.create_task(
        bus.run_action("echo", "count", {"n": 1, "block": True}, on_feedback=on_feedback, timeout=5))
    while len(seen) < 4:
        await asyncio.sleep(0)
    host = bus._nodes["echo"]
    await host.leave()
    with pytest.raises(NodeUnavailableError):
        await task


async def test_cancelling_caller_cancels_node_work(bus: MemoryMiddleware) -> None:
    started = asyncio.Event()
    cancelled = asyncio.Event()

    async def drive(args: dict[str, Any], feedback: FeedbackSender) -> None:
        started.set()
        try:
            await asyncio.Event().wait()
        except asyncio.CancelledError:
            cancelled.set()
            raise

    await bus.host(NodeInfo("nav", rpcs=(RpcInfo("drive", "action"),)), {}, {"drive": drive})

    async def noop(fb: Feedback) -> None: ...

    task = asyncio.create_task(bus.run_action("nav", "drive", {}, on_feedback=noop, timeout=5))
    await asyncio.wait_for(started.wait(), 1)
    task.cancel()
    await asyncio.wait_for(cancelled.wait(), 1)
    assert task.cancelled()


async def test_topics_and_presence(bus: MemoryMiddleware) -> None:
    got: list[Message] = []
    events: list[object] = []
    sub = await bus.subscribe("battery", got.append)
    watch = await bus.watch(events.append)
    assert events == [NodeJoined(INFO)]
    host = await bus.host(NodeInfo("base", topics=("battery",)), {}, {})
    host.publish("battery", {"percent": 80}, stamp=1.0)
    assert got == [Message("battery", {"percent": 80}, 1.0)]
    sub.close()
    host.publish("battery", {"percent": 79})
    assert len(got) == 1
    await host.leave()
    assert events[-1] == NodeLeft("base")
    watch.close()
    assert set(bus.nodes()) == {"echo"}


def test_unknown_scheme_lists_supported() -> None:
    with pytest.raises(UnsupportedURIError) as err:
        open_middleware("ros9://robot")
    assert "memory://" in str(err.value) and "zenoh://" in str(err.value)
    assert isinstance(open_middleware("memory://"), MemoryMiddleware)
