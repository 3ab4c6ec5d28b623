"""rclpy in its own thread, bridged into asyncio in one place.

`RosBridge` owns one rclpy `Context` (initialised for the adapter's domain, never the global
one, so several adapters can live in one process), one node, and an executor spinning in a
daemon thread. The executor is single-threaded: every callback here is short (convert a
message, hand it to the loop) and never blocks, and a thread pool would add a hop to each
response (measured: docs/performance.md). Everything the executor thread hands to the event loop goes
through `post` (``loop.call_soon_threadsafe``); `wait` turns an rclpy future into an awaitable.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import logging
import os
import tempfile
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from robovoice.errors import MiddlewareError
from robovoice.middleware.ros2_config import Ros2Settings, fastdds_profile

import rclpy  # isort: skip  # after the guarded import in ros2.py
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.context import Context
from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.task import Future

log = logging.getLogger(__name__)

HOST_THREADS = 8
"""Threads for hosted nodes' callbacks: each running call or action holds one."""
_ENV_LOCK = threading.Lock()
_names = itertools.count(1)


@contextlib.contextmanager
def ros_environment(settings: Ros2Settings) -> Iterator[None]:
    """The variables rcl and Fast DDS read while a context and its participant start, set for
    that moment only (then restored: the process's environment is not ours to keep).

    The short-lease profile file is set only when the process has none: a user's own
    ``FASTDDS_DEFAULT_PROFILES_FILE`` wins."""
    wanted = settings.environment()
    if settings.lease_s > 0 and "FASTDDS_DEFAULT_PROFILES_FILE" not in os.environ:
        wanted["FASTDDS_DEFAULT_PROFILES_FILE"] = str(write_profile(settings.lease_s))
    with _ENV_LOCK:
        saved = {name: os.environ.get(name) for name in wanted}
        os.environ.update(wanted)
        try:
            yield
        finally:
            for name, value in saved.items():
                if value is None:
                    os.environ.pop(name, None)
                else:
                    os.environ[name] = value


def write_profile(lease_s: float) -> Path:
    """The short-lease Fast DDS profile as a file (one per lease value, reused)."""
    path = Path(tempfile.gettempdir()) / f"robovoice-fastdds-lease-{lease_s:g}s-{os.getuid()}.xml"
    text = fastdds_profile(lease_s)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(text, encoding="utf-8")
        tmp.replace(path)
    return path


def _keep_no_executor(executor: object) -> None:
    return None


def _now(future: Future[Any]) -> None:
    """Make `future`'s done callbacks run where its result is set, not as a later executor task:
    executors attach themselves with `_set_executor` just before setting the result, and a
    future with no executor calls its callbacks at once (rclpy.task.Future)."""
    future._set_executor = _keep_no_executor  # type: ignore[method-assign]  # see above


class RosBridge:
    """One rclpy context + node + executor thread, and the way back into the event loop."""

    def __init__(self, settings: Ros2Settings, loop: asyncio.AbstractEventLoop) -> None:
        self._settings = settings
        self._loop = loop
        self._closed = False
        with ros_environment(settings):  # read by rcl and Fast DDS during init and node creation
            self.context = Context()
            try:
                rclpy.init(context=self.context, domain_id=settings.domain_id)
            except Exception as exc:
                raise MiddlewareError(f"{settings.uri}: cannot start ROS 2: {exc}") from exc
            try:
                self.node: Node = rclpy.create_node(
                    f"robovoice_{os.getpid()}_{next(_names)}", context=self.context,
                    enable_rosout=False, start_parameter_services=False,
                )
            except Exception as exc:
                self.context.try_shutdown()
                raise MiddlewareError(f"{settings.uri}: cannot create the ROS 2 node: {exc}") from exc
        self._host_executor: MultiThreadedExecutor | None = None
        self.group = ReentrantCallbackGroup()
        self._executor = SingleThreadedExecutor(context=self.context)
        self._executor.add_node(self.node)
        self._thread = threading.Thread(target=self._spin_on, args=(self._executor,), name="robovoice-rclpy",
                                        daemon=True)
        self._thread.start()

    def host_executor(self) -> MultiThreadedExecutor:
        """The executor of the nodes hosted here (`ros2_host`), started on first use: its
        callbacks wait for handlers on the event loop, so they get threads of their own."""
        if self._host_executor is None:
            self._host_executor = MultiThreadedExecutor(num_threads=HOST_THREADS, context=self.context)
            threading.Thread(target=self._spin_on, args=(self._host_executor,), name="robovoice-rclpy-host",
                             daemon=True).start()
        return self._host_executor

    def _spin_on(self, executor: SingleThreadedExecutor | MultiThreadedExecutor) -> None:
        """Spin `executor` until close. rclpy re-raises a failed callback in the spinning thread,
        which ends `spin()`: a hosted node that leaves while answering (its service destroyed
        before rclpy sends the response: `InvalidHandle`) would stop the serving of every other
        node, and on the client side every call. That one answer is lost (its caller gets
        `node_unavailable` from the graph); the rest is served on."""
        while True:
            try:
                executor.spin()
                return  # shut down
            except Exception as exc:
                if self._closed or not self.context.ok():
                    return
                log.info("an rclpy callback failed (%s: %s); spinning on", type(exc).__name__, exc)

    @property
    def loop(self) -> asyncio.AbstractEventLoop:
        return self._loop

    def post(self, fn: Callable[..., object], *args: object) -> None:
        """Run `fn(*args)` on the event loop (from any thread); dropped once the loop is closed."""
        if self._loop.is_closed():
            return
        with contextlib.suppress(RuntimeError):  # the loop closed meanwhile
            self._loop.call_soon_threadsafe(fn, *args)

    def wait(self, future: Future[Any], *, at_once: bool = False) -> asyncio.Future[Any]:
        """An asyncio future settled (on the loop) when the rclpy `future` is done.

        rclpy runs a future's done callbacks as a new executor task, one more turn of the
        executor (a wait set rebuilt and waited on) before the answer is handed over. With
        `at_once` (a service response) the hand-over, one thread-safe `post`, is made on the
        executor thread when the result is set (`_now`); should the result be set first, the
        callback runs as rclpy's task, one turn later. Not for an action's result: rclpy sets it
        before it delivers the feedback taken in the same turn, which would then come too late."""
        waiter: asyncio.Future[Any] = self._loop.create_future()
        if at_once:
            _now(future)

        def settle(done: Future[Any]) -> None:
            if waiter.done():
                return
            if done.cancelled():
                waiter.cancel()
            elif done.exception() is not None:
                waiter.set_exception(done.exception())  # type: ignore[arg-type]  # checked not None
            else:
                waiter.set_result(done.result())

        future.add_done_callback(lambda done: self.post(settle, done))
        return waiter

    def close(self) -> None:
        if self._closed:
            return
        self._closed = True
        if self._host_executor is not None:
            self._host_executor.shutdown(timeout_sec=2.0)
        self._executor.shutdown(timeout_sec=2.0)
        try:
            self.node.destroy_node()
        finally:
            self.context.try_shutdown()
        self._thread.join(timeout=2.0)
