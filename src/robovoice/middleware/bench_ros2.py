"""`robovoice bench ros2`: the ROS 2 adapter measured against bare rclpy, nodes in another process.

- **call**: an MCP tool call (in-process server and client) bound to a ``std_srvs/SetBool``
  service, the adapter's own `call` without MCP, and a bare rclpy client (its own context,
  blocking ``client.call``) on the same service, interleaved in blocks in the same run. The MCP
  call is timed twice: with the SDK client's default (``mode="auto"``, which settles on the
  2026-07-28 protocol) and on a 2025-11-25 session (``mode="legacy"``), each beside the same
  call to a no-op tool on the memory bus (MCP's own share);
- **ingest**: a 30 Hz ``sensor_msgs/CompressedImage`` (50 kB) into the snapshot store for a
  while, with the process's resident memory before and after (it must stay flat);
- **kill**: how long until a ``kill -9``'d node's tools are gone (the node runs with the
  short-lease Fast DDS profile, as docs/ros2.md tells robots to).

The child is ``python -m robovoice.middleware.bench_ros2 DOMAIN``: plain rclpy, the service
and the image topic. Run on its own ROS_DOMAIN_ID (default 231).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import AsyncIterator, Awaitable, Callable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Literal

from robovoice.middleware.bench_stats import BLOCK, Stats
from robovoice.middleware.ros2 import Ros2Middleware
from robovoice.middleware.ros2_bridge import write_profile

SERVICE = "/bench/set_bool"
IMAGE = "/bench/image/compressed"
IMAGE_BYTES = 50_000
IMAGE_HZ = 30.0






@dataclass(frozen=True, slots=True)
class IngestResult:
    seconds: float
    received: int
    per_second: float
    rss_before_kib: int
    rss_after_kib: int


@dataclass(frozen=True, slots=True)
class Ros2BenchReport:
    bare_rclpy: Stats
    adapter_call: Stats
    mcp_call: Stats
    """With the SDK client's default protocol (2026-07-28): the figure the goal is read on."""
    mcp_memory_call: Stats
    """The same MCP tool call to a no-op RPC on the in-process memory bus: MCP's own share."""
    mcp_session_call: Stats
    """The MCP tool call on a 2025-11-25 session (the handshake-era protocol)."""
    mcp_session_memory_call: Stats
    mcp_minus_bare_ms: float
    mcp_session_minus_bare_ms: float
    mcp_ratio: float
    ingest: IngestResult
    kill_noticed_s: float

    def to_dict(self) -> dict[str, object]:
        return asdict(self)


def _manifests(folder: Path) -> Path:
    manifest = {
        "node": "bench",
        "tools": [{"name": "set_flag", "rpc": SERVICE, "description": "Set a flag.",
                   "ros2": {"type": "std_srvs/srv/SetBool", "arguments": {"on": {"field": "data"}}}}],
        "snapshots": [{"name": "get_image", "topic": IMAGE, "description": "An image.", "max_age_s": 1.0,
                       "ros2": {"type": "sensor_msgs/msg/CompressedImage"}}],
    }
    (folder / "bench.mcp.json").write_text(json.dumps(manifest), encoding="utf-8")
    return folder


def _rss_kib() -> int:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    return 0


class _BareClient:
    """rclpy as a user would write it: own context, a spinning thread, blocking calls."""

    def __init__(self, domain: int) -> None:
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import QoSProfile
        from std_srvs.srv import SetBool

        self._context = Context()
        rclpy.init(context=self._context, domain_id=domain)
        self._node = rclpy.create_node("bare_bench_client", context=self._context)
        self._client: Any = self._node.create_client(SetBool, SERVICE, qos_profile=QoSProfile(depth=100))
        self._executor = SingleThreadedExecutor(context=self._context)
        self._executor.add_node(self._node)
        self._thread = threading.Thread(target=self._executor.spin, daemon=True)
        self._thread.start()
        self._request = SetBool.Request(data=True)
        if not self._client.wait_for_service(timeout_sec=10):
            raise RuntimeError(f"{SERVICE} did not appear")

    def call(self) -> float:
        t0 = time.perf_counter()
        self._client.call(self._request, timeout_sec=5)
        return time.perf_counter() - t0

    def close(self) -> None:
        self._executor.shutdown(timeout_sec=2)
        self._node.destroy_node()
        self._context.try_shutdown()


async def run_ros2_bench(*, domain: int = 231, rounds: int = 6, ingest_s: float = 10.0) -> Ros2BenchReport:
    from mcp import Client

    from robovoice.mcp_server.audit import AuditLog
    from robovoice.mcp_server.server import RobotToolServer

    env = dict(os.environ, ROS_DOMAIN_ID=str(domain), ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST",
               FASTDDS_DEFAULT_PROFILES_FILE=str(write_profile(2.0)), PYTHONUNBUFFERED="1")
    with tempfile.TemporaryDirectory() as tmp:
        env.setdefault("ROS_LOG_DIR", tmp)
        os.environ.setdefault("ROS_LOG_DIR", tmp)
        child = subprocess.Popen([sys.executable, "-m", "robovoice.middleware.bench_ros2", str(domain)],
                                 stdout=subprocess.PIPE, text=True, env=env, start_new_session=True)
        try:
            assert child.stdout is not None
            line = await asyncio.wait_for(asyncio.to_thread(child.stdout.readline), 30)
            if "ready" not in line:
                raise RuntimeError(f"the benchmark's ROS 2 node did not start (said {line!r})")
            middleware = Ros2Middleware.from_uri(f"ros2://?domain_id={domain}&manifests={_manifests(Path(tmp))}")
            await middleware.start()
            bare = await asyncio.to_thread(_BareClient, domain)
            try:
                server = RobotToolServer(middleware, audit=AuditLog(None))
                async with (server.running(), Client(server.server) as client,
                            Client(server.server, mode="legacy") as session_client):
                    async with asyncio.timeout(20):
                        while "bench" not in middleware.nodes():
                            await asyncio.sleep(0.05)
                        while not any(t.name == "set_flag" for t in (await client.list_tools()).tools):
                            await asyncio.sleep(0.05)
                        await session_client.list_tools()
                    binding_args = {"on": True}
                    mcp, mcp_session = _timed(client, binding_args), _timed(session_client, binding_args)

                    async def adapter() -> float:
                        t0 = time.perf_counter()
                        await middleware.call("bench", SERVICE, binding_args, timeout=5)
                        return time.perf_counter() - t0

                    async with _memory_tool("auto") as memory, _memory_tool("legacy") as memory_session:
                        series = {"adapter": adapter, "mcp": mcp, "memory": memory, "mcp_session": mcp_session,
                                  "memory_session": memory_session}
                        samples: dict[str, list[float]] = {name: [] for name in ("bare", *series)}
                        for _ in range(20):  # warm-up
                            bare.call()
                            for timed in series.values():
                                await timed()
                        for _ in range(rounds):  # interleaved blocks, in this order
                            samples["bare"] += [bare.call() for _ in range(BLOCK)]
                            for name, timed in series.items():
                                samples[name] += [await timed() for _ in range(BLOCK)]
                    ingest = await _ingest(server, ingest_s)
                    killed = time.monotonic()
                    os.killpg(child.pid, signal.SIGKILL)
                    async with asyncio.timeout(30):
                        while "bench" in middleware.nodes():
                            await asyncio.sleep(0.01)
                    kill_s = time.monotonic() - killed
            finally:
                await asyncio.to_thread(bare.close)
                await middleware.close()
        finally:
            if child.poll() is None:
                os.killpg(child.pid, signal.SIGKILL)
            child.wait(5)
            if child.stdout is not None:
                child.stdout.close()
    stats = {name: Stats.of(s) for name, s in samples.items()}
    bare_ms = stats["bare"].median_ms
    return Ros2BenchReport(
        bare_rclpy=stats["bare"], adapter_call=stats["adapter"], mcp_call=stats["mcp"],
        mcp_memory_call=stats["memory"], mcp_session_call=stats["mcp_session"],
        mcp_session_memory_call=stats["memory_session"],
        mcp_minus_bare_ms=stats["mcp"].median_ms - bare_ms,
        mcp_session_minus_bare_ms=stats["mcp_session"].median_ms - bare_ms,
        mcp_ratio=stats["mcp"].median_ms / bare_ms,
        ingest=ingest, kill_noticed_s=kill_s,
    )


def _timed(client: Any, arguments: dict[str, Any]) -> Callable[[], Awaitable[float]]:
    """One timed `set_flag` call through `client`; a failed call ends the benchmark."""

    async def call() -> float:
        t0 = time.perf_counter()
        result = await client.call_tool("set_flag", arguments)
        if result.is_error:
            raise RuntimeError(f"set_flag failed: {result.content}")
        return time.perf_counter() - t0

    return call


@contextlib.asynccontextmanager
async def _memory_tool(mode: Literal["auto", "legacy"]) -> AsyncIterator[Callable[[], Awaitable[float]]]:
    """A timed MCP call of a no-op tool on the memory bus (server and client in-process)."""
    from mcp import Client

    from robovoice.mcp_server.audit import AuditLog
    from robovoice.mcp_server.server import RobotToolServer
    from robovoice.middleware.base import NodeInfo, RpcInfo
    from robovoice.middleware.memory import MemoryMiddleware

    async def noop(args: dict[str, Any]) -> Any:
        return {"success": True, "message": ""}

    parameters = {"type": "object", "properties": {"on": {"type": "boolean"}}}
    manifest = {"node": "noop", "tools": [{"name": "set_flag", "rpc": "set", "description": "Set a flag.",
                                           "parameters": parameters}]}
    middleware = MemoryMiddleware()
    await middleware.start()
    host = await middleware.host(NodeInfo("noop", (RpcInfo("set", params=("on",)),), (), manifest), {"set": noop}, {})
    server = RobotToolServer(middleware, audit=AuditLog(None))
    try:
        async with server.running(), Client(server.server, mode=mode) as client:
            await client.list_tools()
            yield _timed(client, {"on": True})
    finally:
        await host.leave()
        await middleware.close()


async def _ingest(server: Any, seconds: float) -> IngestResult:
    received = 0

    def count(_: Any) -> None:
        nonlocal received
        received += 1

    subscription = await server.middleware.subscribe(IMAGE, count)
    try:
        await asyncio.sleep(1.0)  # the first frames, the buffers in place
        before, received = _rss_kib(), 0
        await asyncio.sleep(seconds)
        return IngestResult(seconds, received, received / seconds, before, _rss_kib())
    finally:
        subscription.close()


def _child(domain: int) -> int:
    """The benchmark's robot: the SetBool service and the 30 Hz 50 kB image, plain rclpy."""
    import rclpy
    from rclpy.executors import MultiThreadedExecutor
    from rclpy.qos import QoSProfile
    from sensor_msgs.msg import CompressedImage
    from std_srvs.srv import SetBool

    rclpy.init(domain_id=domain)
    node = rclpy.create_node("bench_robot")

    def answer(request: Any, response: Any) -> Any:
        response.success = True
        return response

    node.create_service(SetBool, SERVICE, answer, qos_profile=QoSProfile(depth=100))
    publisher = node.create_publisher(CompressedImage, IMAGE, 5)
    frame = CompressedImage(format="jpeg", data=bytes(IMAGE_BYTES))

    def tick() -> None:
        frame.header.stamp = node.get_clock().now().to_msg()
        publisher.publish(frame)

    node.create_timer(1.0 / IMAGE_HZ, tick)
    executor = MultiThreadedExecutor(num_threads=2)
    executor.add_node(node)
    print("ready", flush=True)
    executor.spin()
    return 0


if __name__ == "__main__":
    raise SystemExit(_child(int(sys.argv[1])))
