"""The node side of the Zenoh adapter: serve a node's RPCs and actions, publish its topics.

A hosted node declares, in this order: its info queryable, one queryable per RPC, one per
action (on ``.../goal/*``), a subscriber for cancel requests, a liveliness subscriber on the
robot's clients, and last its liveliness token (so a client that sees the token can fetch
the info). Each query runs as a task owned by the host; `leave()` withdraws the token first,
answers every query still running with ``node_unavailable``, then undeclares the rest.

A goal ends early when its client asks (a put on ``.../cancel/<goal>``) or when the client's
liveliness token disappears (the client crashed or closed): the handler is cancelled.
"""

from __future__ import annotations

import asyncio
import collections
import logging
import sys
import time
from collections.abc import Awaitable, Callable, Coroutine, Mapping
from dataclasses import dataclass

import zenoh

from robovoice.errors import (
    CallTimeoutError,
    CancelledByRobotError,
    InvalidArgumentsError,
    NodeUnavailableError,
    RobotFailure,
)
from robovoice.middleware.base import JSON, ActionHandler, Feedback, NodeInfo, RpcHandler
from robovoice.middleware.zenoh_bridge import LoopBridge, finish, undeclare
from robovoice.middleware.zenoh_codec import ENCODING, decode, encode, failure_to_bytes, feedback_to_bytes, info_to_json
from robovoice.middleware.zenoh_keys import KeyLayout
from robovoice.middleware.zenoh_query import JSON_ENCODING

log = logging.getLogger(__name__)

Work = Callable[[dict[str, JSON], Callable[[], None]], Awaitable[JSON]]
"""Runs a handler on the arguments; the second argument counts one feedback message."""


@dataclass
class _Goal:
    task: asyncio.Task[None]
    client: str | None


class ZenohNodeHost:
    """One node served over a Zenoh session (see the module docstring)."""

    def __init__(
        self,
        session: zenoh.Session,
        layout: KeyLayout,
        bridge: LoopBridge,
        info: NodeInfo,
        rpcs: Mapping[str, RpcHandler],
        actions: Mapping[str, ActionHandler],
    ) -> None:
        self._session = session
        self._layout = layout
        self._bridge = bridge
        self._info = info
        self._rpcs = dict(rpcs)
        self._actions = dict(actions)
        self._info_payload = encode(info_to_json(info))
        self._declared: list[zenoh.Queryable[None] | zenoh.Subscriber[None]] = []
        self._publishers: dict[str, zenoh.Publisher] = {}
        self._token: zenoh.LivelinessToken | None = None
        self._tasks: dict[asyncio.Task[None], str] = {}  # running queries -> RPC/action name
        self._reasons: dict[asyncio.Task[None], RobotFailure] = {}
        self._goals: dict[str, _Goal] = {}
        self._early_cancels: collections.deque[str] = collections.deque(maxlen=256)
        self._left = False

    @property
    def info(self) -> NodeInfo:
        return self._info

    def declare(self) -> None:
        """Declare everything and announce the node (its liveliness token last)."""
        name, layout, bridge = self._info.name, self._layout, self._bridge
        declare_queryable = self._session.declare_queryable
        self._declared.append(declare_queryable(layout.info(name), bridge.handler(self._on_info)))
        for rpc in self._rpcs:
            key = layout.rpc(name, rpc)
            self._declared.append(declare_queryable(key, bridge.handler(self._rpc_receiver(rpc, key))))
        for action in self._actions:
            key = layout.goal_all(name, action)
            self._declared.append(declare_queryable(key, bridge.handler(self._goal_receiver(action))))
        if self._actions:
            self._declared.append(self._session.declare_subscriber(
                layout.cancel_all(name), bridge.handler(self._on_cancel)))
            self._declared.append(self._session.liveliness().declare_subscriber(
                layout.client_all(), bridge.handler(self._on_client_change)))
        self._token = self._session.liveliness().declare_token(layout.alive(name))
        log.info("node %s announced on %s", name, layout.alive(name))

    # --- topics ------------------------------------------------------------------------
    def publish(self, topic: str, value: JSON, stamp: float | None = None) -> None:
        if self._left:
            log.debug("%s left; not publishing on %s", self._info.name, topic)
            return
        publisher = self._publishers.get(topic)
        if publisher is None:
            publisher = self._session.declare_publisher(self._layout.topic(topic), encoding=ENCODING)
            self._publishers[topic] = publisher
        attachment = encode({"stamp": time.time() if stamp is None else stamp})
        publisher.put(encode(value), attachment=attachment)

    # --- queries -----------------------------------------------------------------------
    def _on_info(self, query: zenoh.Query) -> None:
        with query:
            if not self._left:
                query.reply(self._layout.info(self._info.name), self._info_payload, encoding=ENCODING)

    def _rpc_receiver(self, rpc: str, key: str) -> Callable[[zenoh.Query], object]:
        handler = self._rpcs[rpc]

        async def work(args: dict[str, JSON], _count: Callable[[], None]) -> JSON:
            return await handler(args)

        reply_key = zenoh.KeyExpr(key)  # validated once, not per reply
        return lambda query: self._start(query, rpc, reply_key, work, None, None)

    def _goal_receiver(self, action: str) -> Callable[[zenoh.Query], None]:
        handler = self._actions[action]

        def receive(query: zenoh.Query) -> None:
            key = str(query.key_expr)
            goal = self._layout.parse_goal(key, "goal")
            if goal is None or goal.node != self._info.name or goal.action != action:
                _refuse(query, InvalidArgumentsError(f"not a goal key: {key}"))
                return
            if goal.goal_id in self._goals or goal.goal_id in self._early_cancels:
                _refuse(query, CancelledByRobotError(
                    f"goal {goal.goal_id} of {self._info.name}.{action} was cancelled or is running already",
                    details={"node": self._info.name, "action": action, "goal": goal.goal_id}))
                return
            feedback_key = self._layout.feedback(self._info.name, action, goal.goal_id)

            async def work(args: dict[str, JSON], count: Callable[[], None]) -> JSON:
                async def send(feedback: Feedback) -> None:
                    self._session.put(feedback_key, feedback_to_bytes(feedback), encoding=ENCODING)
                    count()

                return await handler(args, send)

            client = query.parameters.get("client") or None
            task = self._start(query, action, key, work, goal.goal_id, client)
            if task is not None:
                self._goals[goal.goal_id] = _Goal(task, client)

        return receive

    def _start(self, query: zenoh.Query, name: str, reply_key: str | zenoh.KeyExpr, work: Work,
               goal_id: str | None, client: str | None) -> asyncio.Task[None] | None:
        if self._left:
            _refuse(query, self._gone(name))
            return None
        serve, task_name = self._serve(query, name, reply_key, work, goal_id), f"zenoh-{self._info.name}.{name}"
        # a goal is registered by the caller once this returns, so only an RPC may finish eagerly
        task = _eager_task(serve, task_name) if goal_id is None else asyncio.create_task(serve, name=task_name)
        self._tasks[task] = name
        task.add_done_callback(self._finished)
        return task

    def _finished(self, task: asyncio.Task[None]) -> None:
        self._tasks.pop(task, None)
        self._reasons.pop(task, None)
        if not task.cancelled() and task.exception() is not None:  # _serve catches everything
            log.error("serving a query failed", exc_info=task.exception())

    async def _serve(self, query: zenoh.Query, name: str, reply_key: str | zenoh.KeyExpr, work: Work,
                     goal_id: str | None) -> None:
        where = f"{self._info.name}.{name}"
        feedback_count = 0

        def count() -> None:
            nonlocal feedback_count
            feedback_count += 1

        try:
            payload: bytes | None = None
            failure: RobotFailure | None = None
            try:
                args = _arguments(query, where)
                timer = self._deadline(_timeout(query), where, name)
                try:
                    payload = encode(await work(args, count))
                finally:
                    if timer is not None:
                        timer.cancel()
            except asyncio.CancelledError:
                current = asyncio.current_task()
                failure = self._reasons.get(current) if current is not None else None
                if failure is None:
                    raise
            except TimeoutError:
                failure = CallTimeoutError(f"{where} did not finish within its timeout",
                                           details={"node": self._info.name, "rpc": name})
            except RobotFailure as robot_failure:
                failure = robot_failure
            except Exception as exc:  # a node's bug becomes a tool error, not a crash
                log.exception("%s failed", where)
                failure = RobotFailure(f"{where} failed: {exc}", code="internal_error",
                                       details={"node": self._info.name, "rpc": name})
            if failure is not None:
                _reply_failure(query, failure)
            elif payload is not None:
                attachment = encode({"feedback": feedback_count}) if goal_id is not None else None
                query.reply(reply_key, payload, encoding=JSON_ENCODING, attachment=attachment)
        except zenoh.ZError as exc:
            log.debug("could not answer %s: %s", where, exc)
        finally:
            if goal_id is not None:
                self._goals.pop(goal_id, None)
            finish(query)

    def _deadline(self, timeout: float | None, where: str, name: str) -> asyncio.TimerHandle | None:
        """Cancel the current task with a `CallTimeoutError` reason after `timeout` seconds
        (cheaper than ``asyncio.timeout`` on the path of every RPC; the reason is replied)."""
        task = asyncio.current_task()
        if timeout is None or task is None:
            return None
        return asyncio.get_running_loop().call_later(timeout, self._time_out, task, where, name)

    def _time_out(self, task: asyncio.Task[None], where: str, name: str) -> None:
        self._cancel(task, CallTimeoutError(f"{where} did not finish within its timeout",
                                            details={"node": self._info.name, "rpc": name}))

    # --- cancellation --------------------------------------------------------------------
    def _on_cancel(self, sample: zenoh.Sample) -> None:
        goal = self._layout.parse_goal(str(sample.key_expr), "cancel")
        if goal is None or goal.node != self._info.name:
            return
        running = self._goals.get(goal.goal_id)
        if running is None:
            self._early_cancels.append(goal.goal_id)  # the goal may still be on its way
            return
        log.info("%s.%s: goal %s cancelled by its client", goal.node, goal.action, goal.goal_id)
        self._cancel(running.task, CancelledByRobotError(
            f"{goal.node}.{goal.action} was cancelled", details={"goal": goal.goal_id}))

    def _on_client_change(self, sample: zenoh.Sample) -> None:
        if sample.kind != zenoh.SampleKind.DELETE:
            return
        client = self._layout.last_chunk(str(sample.key_expr))
        for goal_id, goal in list(self._goals.items()):
            if goal.client == client:
                log.warning("%s: client %s is gone; cancelling goal %s", self._info.name, client, goal_id)
                self._cancel(goal.task, CancelledByRobotError(
                    "the client that started this goal is gone", details={"client": client, "goal": goal_id}))

    def _cancel(self, task: asyncio.Task[None], reason: RobotFailure) -> None:
        self._reasons.setdefault(task, reason)
        task.cancel()

    def _gone(self, name: str) -> NodeUnavailableError:
        return NodeUnavailableError(
            f"node {self._info.name!r} left while {name} was running",
            hint="the robot part went offline; tell the user",
            details={"node": self._info.name, "rpc": name},
        )

    async def leave(self) -> None:
        if self._left:
            return
        self._left = True
        if self._token is not None:
            undeclare(self._token)
        tasks = list(self._tasks)
        for task, name in list(self._tasks.items()):
            self._cancel(task, self._gone(name))
        if tasks:
            await asyncio.wait(tasks)
        for entity in self._declared:
            undeclare(entity)
        for publisher in self._publishers.values():
            undeclare(publisher)
        self._declared.clear()
        self._publishers.clear()
        log.info("node %s left", self._info.name)


def _eager_task(coro: Coroutine[object, object, None], name: str) -> asyncio.Task[None]:
    """A task for serving one query. From Python 3.12 on it starts eagerly: a handler that
    needs no wait answers in the loop turn that received the query, one loop iteration
    (and a chance for Zenoh's thread to take the GIL) sooner."""
    if sys.version_info >= (3, 12):
        return asyncio.Task(coro, name=name, eager_start=True)
    return asyncio.create_task(coro, name=name)


def _reply_failure(query: zenoh.Query, failure: RobotFailure) -> None:
    try:
        query.reply_err(failure_to_bytes(failure), encoding=JSON_ENCODING)
    except zenoh.ZError as exc:
        log.debug("could not send an error reply: %s", exc)


def _refuse(query: zenoh.Query, failure: RobotFailure) -> None:
    """Answer a query that will not be served, and finish it."""
    with query:
        _reply_failure(query, failure)


def _arguments(query: zenoh.Query, where: str) -> dict[str, JSON]:
    payload = query.payload
    try:
        args = decode(payload.to_bytes()) if payload is not None else None
    except ValueError as exc:
        raise InvalidArgumentsError(f"{where}: the arguments are not JSON: {exc}") from None
    if args is None:
        return {}
    if not isinstance(args, dict):
        raise InvalidArgumentsError(f"{where}: the arguments must be a JSON object")
    return args


def _timeout(query: zenoh.Query) -> float | None:
    value = query.parameters.get("timeout")
    try:
        seconds = float(value) if value else None
    except ValueError:
        return None
    return seconds if seconds is not None and seconds > 0 else None
