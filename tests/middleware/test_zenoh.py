"""Zenoh-specific behaviour beyond the shared contract: start-up failures, config files,
a node's session dying mid-call, a client dying mid-goal, callbacks on the event loop,
and interplay with a node written against the raw `zenoh` API."""

from __future__ import annotations

import asyncio
import json
import socket
import threading
import time
from collections.abc import AsyncIterator
from pathlib import Path

import pytest
import zenoh

from robovoice.errors import ConfigError, MiddlewareError, NodeUnavailableError, RobotFailure
from robovoice.middleware.base import (
    JSON,
    Feedback,
    FeedbackSender,
    Message,
    NodeInfo,
    NodeLeft,
    PresenceEvent,
    RpcInfo,
)
from robovoice.middleware.zenoh import ZenohMiddleware
from robovoice.middleware.zenoh_bridge import close_session

from ..waiting import until

BOUND_S = 5.0


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@pytest.fixture
def port() -> int:
    return free_port()


@pytest.fixture
async def nodes(port: int) -> AsyncIterator[ZenohMiddleware]:
    middleware = ZenohMiddleware.from_uri(f"zenoh://?listen=tcp/127.0.0.1:{port}&robot=t")
    await middleware.start()
    yield middleware
    await middleware.close()


@pytest.fixture
async def client(port: int, nodes: ZenohMiddleware) -> AsyncIterator[ZenohMiddleware]:
    middleware = ZenohMiddleware.from_uri(f"zenoh://?connect=tcp/127.0.0.1:{port}&robot=t")
    await middleware.start()
    yield middleware
    await middleware.close()


async def test_unreachable_endpoint_fails_fast_naming_it(port: int) -> None:
    for uri in (f"zenoh://127.0.0.1:{port}?mode=client&timeout=0.3",
                f"zenoh://?connect=tcp/127.0.0.1:{port}&must_connect=true&timeout=0.3"):
        started = time.monotonic()
        with pytest.raises(MiddlewareError, match=f"tcp/127.0.0.1:{port}"):
            await ZenohMiddleware.from_uri(uri).start()
        assert time.monotonic() - started < 2.0


async def test_taken_listen_port_is_a_clear_error(nodes: ZenohMiddleware, port: int) -> None:
    with pytest.raises(MiddlewareError, match=f"tcp/127.0.0.1:{port}"):
        await ZenohMiddleware.from_uri(f"zenoh://?listen=tcp/127.0.0.1:{port}").start()


async def test_calls_before_start_are_refused() -> None:
    with pytest.raises(MiddlewareError, match="not started"):
        await ZenohMiddleware.from_uri("zenoh://").call("a", "b", {}, timeout=1)


async def test_config_file_passthrough(tmp_path: Path, port: int) -> None:
    config = tmp_path / "zenoh.json5"
    config.write_text("{ mode: 'peer', // a comment, JSON5 style\n"
                      f"  listen: {{ endpoints: ['tcp/127.0.0.1:{port}'] }},\n"
                      "  scouting: { multicast: { enabled: false } } }\n")
    served = ZenohMiddleware.from_uri(f"zenoh://?config={config}&robot=cfg")
    await served.start()
    try:
        async def ping(args: dict[str, JSON]) -> JSON:
            return "pong"

        await served.host(NodeInfo("pinger", rpcs=(RpcInfo("ping"),)), {"ping": ping}, {})
        other = ZenohMiddleware.from_uri(f"zenoh://127.0.0.1:{port}?robot=cfg")
        await other.start()
        try:
            await until(lambda: "pinger" in other.nodes())
            assert await other.call("pinger", "ping", {}, timeout=2) == "pong"
        finally:
            await other.close()
    finally:
        await served.close()


async def test_bad_config_file_is_a_config_error(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match=r"zenoh\.json5"):
        await ZenohMiddleware.from_uri(f"zenoh://?config={tmp_path / 'zenoh.json5'}").start()  # missing
    (tmp_path / "bad.json5").write_text("{ mode: ")
    with pytest.raises(ConfigError, match=r"bad\.json5"):
        await ZenohMiddleware.from_uri(f"zenoh://?config={tmp_path / 'bad.json5'}").start()


async def test_node_session_dying_fails_in_flight_calls_promptly(nodes: ZenohMiddleware,
                                                                  client: ZenohMiddleware) -> None:
    started = asyncio.Event()

    async def hang(args: dict[str, JSON]) -> JSON:
        started.set()
        await asyncio.Event().wait()
        return None

    await nodes.host(NodeInfo("stuck", rpcs=(RpcInfo("hang"),)), {"hang": hang}, {})
    await until(lambda: "stuck" in client.nodes())
    events: list[PresenceEvent] = []
    await client.watch(events.append)
    call = asyncio.create_task(client.call("stuck", "hang", {}, timeout=30))
    await asyncio.wait_for(started.wait(), BOUND_S)
    died = time.monotonic()
    assert nodes._session is not None
    close_session(nodes._session)  # as if the process died: no leave(), the link just goes
    with pytest.raises(NodeUnavailableError):
        await asyncio.wait_for(call, BOUND_S)
    assert time.monotonic() - died < 2.0
    await until(lambda: NodeLeft("stuck") in events)


async def test_a_closing_client_s_goal_is_cancelled_on_the_node(port: int, nodes: ZenohMiddleware) -> None:
    running, cancelled = asyncio.Event(), asyncio.Event()

    async def drive(args: dict[str, JSON], feedback: FeedbackSender) -> JSON:
        await feedback(Feedback(0.0))
        running.set()
        try:
            await asyncio.Event().wait()
        except asyncio.CancelledError:
            cancelled.set()
            raise
        return None

    await nodes.host(NodeInfo("nav", rpcs=(RpcInfo("drive", "action"),)), {}, {"drive": drive})
    # a raw client: a goal with its client id, a liveliness token, then the session just closes
    config = zenoh.Config()
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("connect/endpoints", json.dumps([f"tcp/127.0.0.1:{port}"]))
    raw = await asyncio.to_thread(zenoh.open, config)
    token = raw.liveliness().declare_token("robovoice/t/client/raw-client")
    raw.get("robovoice/t/node/nav/action/drive/goal/g-1?client=raw-client;timeout=30", payload=b"{}")
    await asyncio.wait_for(running.wait(), BOUND_S)
    del token
    close_session(raw)
    await asyncio.wait_for(cancelled.wait(), BOUND_S)


async def test_callbacks_run_on_the_event_loop_thread(nodes: ZenohMiddleware, client: ZenohMiddleware) -> None:
    threads: list[threading.Thread] = []
    got: list[Message] = []

    def on_message(message: Message) -> None:
        threads.append(threading.current_thread())
        got.append(message)

    await client.subscribe("t", on_message)
    await client.watch(lambda event: threads.append(threading.current_thread()))
    host = await nodes.host(NodeInfo("pub", topics=("t",)), {}, {})
    async with asyncio.timeout(BOUND_S):
        while not got:
            host.publish("t", [1, 2])
            await asyncio.sleep(0.01)
    assert threads and all(t is threading.main_thread() for t in threads)


async def test_raw_zenoh_node_errors_and_results(port: int, client: ZenohMiddleware) -> None:
    config = zenoh.Config()
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("connect/endpoints", json.dumps([f"tcp/127.0.0.1:{port}"]))
    raw = await asyncio.to_thread(zenoh.open, config)
    try:
        prefix = "robovoice/t/node/raw"

        def info(query: zenoh.Query) -> None:
            with query:
                query.reply(f"{prefix}/info", json.dumps({"name": "raw", "rpcs": ["crash", "add"]}))

        def crash(query: zenoh.Query) -> None:
            with query:
                query.reply_err(b"driver crashed")

        def add(query: zenoh.Query) -> None:
            with query:
                args = json.loads(query.payload.to_bytes()) if query.payload else {}
                query.reply(f"{prefix}/rpc/add", json.dumps(args["a"] + args["b"]))

        keep = [raw.declare_queryable(f"{prefix}/info", info), raw.declare_queryable(f"{prefix}/rpc/crash", crash),
                raw.declare_queryable(f"{prefix}/rpc/add", add),
                raw.liveliness().declare_token("robovoice/t/alive/raw")]
        await until(lambda: "raw" in client.nodes())
        assert [r.name for r in client.nodes()["raw"].rpcs] == ["crash", "add"]
        assert await client.call("raw", "add", {"a": 2, "b": 3}, timeout=2) == 5
        with pytest.raises(RobotFailure) as err:
            await client.call("raw", "crash", {}, timeout=2)
        assert err.value.code == "internal_error" and "driver crashed" in err.value.message
        del keep
    finally:
        close_session(raw)
    await until(lambda: "raw" not in client.nodes())


async def test_close_fails_calls_still_waiting(nodes: ZenohMiddleware, port: int) -> None:
    started = asyncio.Event()

    async def hang(args: dict[str, JSON]) -> JSON:
        started.set()
        await asyncio.Event().wait()
        return None

    await nodes.host(NodeInfo("stuck", rpcs=(RpcInfo("hang"),)), {"hang": hang}, {})
    client = ZenohMiddleware.from_uri(f"zenoh://?connect=tcp/127.0.0.1:{port}&robot=t")
    await client.start()
    await until(lambda: "stuck" in client.nodes())
    call = asyncio.create_task(client.call("stuck", "hang", {}, timeout=30))
    await asyncio.wait_for(started.wait(), BOUND_S)
    await client.close()
    with pytest.raises(MiddlewareError, match="closed"):
        await asyncio.wait_for(call, BOUND_S)


async def test_client_mode_through_a_router(port: int) -> None:
    """Nodes and clients in client mode reach each other through a router (here a Python
    session in router mode, standing in for zenohd or rmw_zenoh's router)."""
    router = ZenohMiddleware.from_uri(f"zenoh://?mode=router&listen=tcp/127.0.0.1:{port}&robot=rt")
    await router.start()
    node = ZenohMiddleware.from_uri(f"zenoh://127.0.0.1:{port}?mode=client&robot=rt")
    client = ZenohMiddleware.from_uri(f"zenoh://127.0.0.1:{port}?mode=client&robot=rt")
    try:
        await node.start()
        await client.start()
        progress: list[float] = []

        async def count(args: dict[str, JSON], feedback: FeedbackSender) -> JSON:
            for i in range(3):
                await feedback(Feedback(i + 1.0, 3.0))
            return "done"

        host = await node.host(NodeInfo("counter", rpcs=(RpcInfo("count", "action"),)), {}, {"count": count})
        await until(lambda: "counter" in client.nodes())

        async def on_feedback(feedback: Feedback) -> None:
            progress.append(feedback.progress)

        assert await client.run_action("counter", "count", {}, on_feedback=on_feedback, timeout=5) == "done"
        assert progress == [1.0, 2.0, 3.0]
        await host.leave()
        await until(lambda: "counter" not in client.nodes())
    finally:
        await client.close()
        await node.close()
        await router.close()


async def test_the_node_answers_timeout_when_its_rpc_overruns_the_callers_deadline(
        port: int, nodes: ZenohMiddleware) -> None:
    """The node stops a handler at the ``timeout`` the query carries and says so (a raw
    client that waits longer than that deadline sees the node's own timeout reply)."""
    stopped = asyncio.Event()

    async def stuck(args: dict[str, JSON]) -> JSON:
        try:
            await asyncio.Event().wait()
        except asyncio.CancelledError:
            stopped.set()
            raise
        return None

    await nodes.host(NodeInfo("slow", rpcs=(RpcInfo("stuck"),)), {"stuck": stuck}, {})
    config = zenoh.Config()
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("connect/endpoints", json.dumps([f"tcp/127.0.0.1:{port}"]))
    raw = await asyncio.to_thread(zenoh.open, config)
    try:
        async with asyncio.timeout(BOUND_S):
            while True:  # until the new session knows the node's queryable (no reply at all before)
                replies = await asyncio.to_thread(lambda: list(
                    raw.get("robovoice/t/node/slow/rpc/stuck?timeout=0.2", payload=b"{}", timeout=BOUND_S)))
                if replies:
                    break
    finally:
        close_session(raw)
    assert stopped.is_set()
    errors = [reply.err for reply in replies if reply.err is not None]
    assert len(errors) == 1
    body = json.loads(errors[0].payload.to_bytes())
    assert body["error"] == "timeout" and "did not finish within its timeout" in body["message"]
