"""Service calls and action goals over rclpy, each with a timeout, and with the server
watched while waiting: a server that leaves the graph mid-call (``kill -9``) ends the wait
with `NodeUnavailableError` — rclpy itself would wait for a result forever.

Clients are made once per interface, with queues 100 deep (rclpy's default of 10 drops
concurrent calls) on a reentrant callback group.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import json
import logging
import math
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from robovoice.errors import CallTimeoutError, CancelledByRobotError, NodeUnavailableError, RobotFailure
from robovoice.middleware.base import JSON, Feedback, FeedbackSender
from robovoice.middleware.ros2_bindings import ToolBinding
from robovoice.middleware.ros2_bridge import RosBridge
from robovoice.middleware.ros2_host import interfaces, rpc_name
from robovoice.middleware.ros2_presence import GraphPresence
from robovoice.middleware.ros2_types import to_json

from action_msgs.msg import GoalStatus  # isort: skip
from rclpy.action.client import ActionClient
from rclpy.client import Client
from rclpy.qos import QoSProfile

log = logging.getLogger(__name__)

QUEUE_DEPTH = 100
WATCH_S = 0.2
"""While waiting for a response, how often the server's presence in the graph is checked."""
CANCEL_WAIT_S = 2.0
MATCH_POLL_S = 0.005


class Ros2Calls:
    """The client side of services and actions for one `RosBridge`."""

    def __init__(self, bridge: RosBridge, presence: GraphPresence) -> None:
        self._bridge = bridge
        self._presence = presence
        self._clients: dict[tuple[str, str], Client[Any, Any]] = {}
        self._actions: dict[tuple[str, str], ActionClient[Any, Any, Any]] = {}

    def close(self) -> None:
        for client in self._clients.values():
            self._bridge.node.destroy_client(client)
        for action in self._actions.values():
            action.destroy()
        self._clients.clear()
        self._actions.clear()

    def _client(self, binding: ToolBinding) -> Client[Any, Any]:
        key = (binding.ros_name, binding.type_name)
        client = self._clients.get(key)
        if client is None:
            client = self._bridge.node.create_client(
                binding.interface, binding.ros_name, qos_profile=QoSProfile(depth=QUEUE_DEPTH),
                callback_group=self._bridge.group)
            self._clients[key] = client
        return client

    def _action_client(self, binding: ToolBinding) -> ActionClient[Any, Any, Any]:
        key = (binding.ros_name, binding.type_name)
        client = self._actions.get(key)
        if client is None:
            qos = QoSProfile(depth=QUEUE_DEPTH)
            client = ActionClient(
                self._bridge.node, binding.interface, binding.ros_name, callback_group=self._bridge.group,
                goal_service_qos_profile=qos, result_service_qos_profile=qos, cancel_service_qos_profile=qos)
            self._actions[key] = client
        return client

    async def _service_call(self, client: Client[Any, Any], request: Any, node: str, target: ToolBinding | _Plain,
                            timeout: float, what: str) -> Any:
        """One service call, bounded; a call given up on leaves no pending request behind."""
        deadline = time.monotonic() + timeout
        await _matched(client.service_is_ready, lambda: self._presence.service_up(target.ros_name), deadline)
        future = client.call_async(request)
        waiter = self._bridge.wait(future, at_once=True)
        try:
            return await self._await(waiter, self._presence.service_up, node, target, deadline, what)
        except BaseException:
            waiter.cancel()
            client.remove_pending_request(future)
            raise

    async def _await(self, waiter: asyncio.Future[Any], up: Any, node: str, binding: ToolBinding | _Plain,
                     deadline: float, what: str) -> Any:
        """Wait for `waiter` until `deadline`, failing early when the server leaves the graph."""
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                raise CallTimeoutError(
                    f"{binding.ros_name} did not answer within the time limit ({what})",
                    hint="the robot is busy or stuck; tell the user", details={"node": node, "rpc": binding.key})
            if await _settled(waiter, min(WATCH_S, left)):
                return waiter.result()
            if not up(binding.ros_name):
                raise NodeUnavailableError(
                    f"{binding.ros_name} went away before answering ({what})",
                    hint="the robot part went offline; tell the user", details={"node": node, "rpc": binding.key})

    # --- robovoice nodes hosted on ROS 2 (ros2_host): JSON in, JSON out ---------------------------
    async def call_json(self, node: str, rpc: str, args: Mapping[str, JSON], *, timeout: float) -> JSON:
        call_type, _ = interfaces()
        target = _Plain(rpc_name(node, rpc), rpc, call_type)
        request = call_type.Request(arguments=json.dumps(dict(args), default=str))
        response = await self._service_call(self._plain_client(target), request, node, target, timeout, "call")
        return _json_outcome(response.result, response.error)

    async def run_json(self, node: str, action: str, args: Mapping[str, JSON], *, on_feedback: FeedbackSender,
                       timeout: float) -> JSON:
        _, run_type = interfaces()
        target = _Plain(rpc_name(node, action), action, run_type)
        client = self._plain_action(target)
        deadline = time.monotonic() + timeout
        feedback: asyncio.Queue[Feedback] = asyncio.Queue(maxsize=256)

        def arrived(message: Any) -> None:  # on the executor thread
            fb = message.feedback
            total = None if math.isnan(fb.total) else fb.total
            item = Feedback(fb.progress, total, fb.message, json.loads(fb.data or "{}"))
            self._bridge.post(_offer, feedback, item)

        await _matched(client.server_is_ready, lambda: self._presence.action_up(target.ros_name), deadline)
        send = client.send_goal_async(run_type.Goal(arguments=json.dumps(dict(args), default=str)),
                                      feedback_callback=arrived)
        handle = await self._goal(send, node, target, deadline)
        relay = asyncio.get_running_loop().create_task(_relay_plain(feedback, on_feedback))
        result_waiter = self._bridge.wait(handle.get_result_async())
        try:
            outcome = await self._await(result_waiter, self._presence.action_up, node, target, deadline, "result")
        except NodeUnavailableError:
            result_waiter.cancel()
            raise
        except BaseException:
            result_waiter.cancel()
            await self._cancel(handle)
            raise
        finally:
            relay.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await relay
        while not feedback.empty():
            await _tell_plain(on_feedback, feedback.get_nowait())
        return _json_outcome(outcome.result.result, outcome.result.error)

    def _plain_client(self, target: _Plain) -> Client[Any, Any]:
        key = (target.ros_name, "robovoice_msgs/srv/Call")
        client = self._clients.get(key)
        if client is None:
            client = self._bridge.node.create_client(target.interface, target.ros_name,
                                                     qos_profile=QoSProfile(depth=QUEUE_DEPTH),
                                                     callback_group=self._bridge.group)
            self._clients[key] = client
        return client

    def _plain_action(self, target: _Plain) -> ActionClient[Any, Any, Any]:
        key = (target.ros_name, "robovoice_msgs/action/Run")
        client = self._actions.get(key)
        if client is None:
            qos = QoSProfile(depth=QUEUE_DEPTH)
            client = ActionClient(self._bridge.node, target.interface, target.ros_name,
                                  callback_group=self._bridge.group, goal_service_qos_profile=qos,
                                  result_service_qos_profile=qos, cancel_service_qos_profile=qos)
            self._actions[key] = client
        return client

    async def call(self, node: str, binding: ToolBinding, args: Mapping[str, JSON], *, timeout: float) -> JSON:
        request = binding.build_request(args)  # checked before anything is sent
        response = await self._service_call(self._client(binding), request, node, binding, timeout, "service call")
        return _outcome(binding, to_json(response), node)

    async def run_action(self, node: str, binding: ToolBinding, args: Mapping[str, JSON], *,
                         on_feedback: FeedbackSender, timeout: float) -> JSON:
        goal = binding.build_request(args)
        client = self._action_client(binding)
        deadline = time.monotonic() + timeout
        feedback: asyncio.Queue[dict[str, JSON]] = asyncio.Queue(maxsize=256)

        def arrived(message: Any) -> None:  # on the executor thread
            data = to_json(message.feedback)
            self._bridge.post(_offer, feedback, data)

        await _matched(client.server_is_ready, lambda: self._presence.action_up(binding.ros_name), deadline)
        send = client.send_goal_async(goal, feedback_callback=arrived)
        handle = await self._goal(send, node, binding, deadline)
        if not handle.accepted:
            raise RobotFailure(f"{binding.ros_name} rejected the goal", code="goal_rejected",
                               hint="the robot refused this request; tell the user",
                               details={"node": node, "rpc": binding.key})
        counter = itertools.count(1)
        relay = asyncio.get_running_loop().create_task(_relay(feedback, binding, on_feedback, counter))
        result_waiter = self._bridge.wait(handle.get_result_async())
        try:
            outcome = await self._await(result_waiter, self._presence.action_up, node, binding, deadline, "result")
        except NodeUnavailableError:  # the server is gone: nobody to cancel the goal with
            result_waiter.cancel()
            raise
        except BaseException:  # timed out, or the caller cancelled: cancel the goal on the robot
            result_waiter.cancel()
            await self._cancel(handle)
            raise
        finally:
            relay.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await relay
        while not feedback.empty():  # what arrived before the result, in order
            await _tell(binding, on_feedback, counter, feedback.get_nowait())
        return _result(binding, outcome.status, to_json(outcome.result), node)

    async def _goal(self, send: Any, node: str, target: ToolBinding | _Plain, deadline: float) -> Any:
        """The goal's handle, once the server has answered. A caller that gives up before that
        (cancelled, timed out) still cancels the goal if the server accepts it meanwhile: the
        server may already be running it."""
        waiter = self._bridge.wait(send)
        try:
            return await self._await(waiter, self._presence.action_up, node, target, deadline, "goal")
        except NodeUnavailableError:  # the server is gone: nobody to cancel the goal with
            raise
        except BaseException:
            try:
                async with asyncio.timeout(CANCEL_WAIT_S):
                    handle = await waiter
            except (Exception, asyncio.CancelledError) as exc:  # no answer in time, the server failed it...
                log.info("the goal given up on was not cancelled: %r", exc)
            else:
                if handle.accepted:
                    await self._cancel(handle)
            raise

    async def _cancel(self, handle: Any) -> None:
        """Ask the server to cancel the goal; bounded, since the server may be gone."""
        try:
            async with asyncio.timeout(CANCEL_WAIT_S):
                await self._bridge.wait(handle.cancel_goal_async())
        except (TimeoutError, asyncio.CancelledError):
            log.info("no answer to the cancel request within %g s", CANCEL_WAIT_S)
        except Exception as exc:  # the goal ended meanwhile, the server is gone...
            log.info("cancelling the goal failed: %s", exc)


async def _matched(ready: Callable[[], bool], up: Callable[[], bool], deadline: float) -> None:
    """Until a client is matched with its server, the server leaves the graph, or `deadline`
    (the wait that follows says which): a request sent before the match is lost, not queued
    (DDS keeps nothing for a reader that joins later), so the first call on a new client could
    time out. Once matched, this is one check of microseconds."""
    while not ready() and up() and time.monotonic() < deadline:
        await asyncio.sleep(MATCH_POLL_S)


async def _settled(waiter: asyncio.Future[Any], timeout: float) -> bool:
    """Whether `waiter` is done within `timeout` s (`asyncio.wait` for one future, without its
    task and set machinery: this is on every call's path)."""
    if not waiter.done():
        loop = asyncio.get_running_loop()
        wake = loop.create_future()

        def ring(_: object = None) -> None:
            if not wake.done():
                wake.set_result(None)

        timer = loop.call_later(timeout, ring)
        waiter.add_done_callback(ring)
        try:
            await wake
        finally:
            timer.cancel()
            waiter.remove_done_callback(ring)
    return waiter.done()


@dataclass(frozen=True, slots=True)
class _Plain:
    """A hosted node's RPC or action: its ROS name, robovoice name and interface type."""

    ros_name: str
    key: str
    interface: Any


def _json_outcome(result: str, error: str) -> JSON:
    """A hosted node's JSON reply: its value, or its structured failure raised. A reply that is
    not what a robovoice node sends (bad JSON, an error that is no object) is an `internal_error`."""
    try:
        if error:
            body = json.loads(error)
            if not isinstance(body, dict):
                raise ValueError("the error is not a JSON object")
            raise RobotFailure.from_dict(body)
        return json.loads(result) if result else None
    except ValueError as exc:  # json.JSONDecodeError included
        raise RobotFailure(f"malformed reply from the node: {exc}", code="internal_error") from None


async def _relay_plain(queue: asyncio.Queue[Feedback], on_feedback: FeedbackSender) -> None:
    while True:
        await _tell_plain(on_feedback, await queue.get())


async def _tell_plain(on_feedback: FeedbackSender, item: Feedback) -> None:
    try:
        await on_feedback(item)
    except Exception:  # a failing progress report must not end the action
        log.exception("feedback callback failed")


def _offer(queue: asyncio.Queue[Any], data: Any) -> None:
    if queue.full():  # a slow consumer: keep the newest feedback
        queue.get_nowait()
    queue.put_nowait(data)


async def _relay(queue: asyncio.Queue[dict[str, JSON]], binding: ToolBinding, on_feedback: FeedbackSender,
                 counter: Iterator[int]) -> None:
    while True:
        await _tell(binding, on_feedback, counter, await queue.get())


async def _tell(binding: ToolBinding, on_feedback: FeedbackSender, counter: Iterator[int],
                data: dict[str, JSON]) -> None:
    try:
        await on_feedback(Feedback(float(next(counter)), None, binding.feedback_text(data), data))
    except Exception:  # a failing progress report must not end the action
        log.exception("feedback callback failed")


def _outcome(binding: ToolBinding, value: JSON, node: str) -> JSON:
    """The response as the tool's result; a false `success_field` is a robot failure."""
    if binding.success_field is not None and isinstance(value, dict):
        current: Any = value
        for part in binding.success_field.split("."):
            current = current.get(part) if isinstance(current, dict) else None
        if current is False:
            message = value.get("message") if isinstance(value.get("message"), str) else None
            raise RobotFailure(message or f"{binding.ros_name} reported failure", code="robot_error",
                               hint="the robot could not do it; tell the user why",
                               details={"node": node, "rpc": binding.key, "response": value})
    return value


def _result(binding: ToolBinding, status: int, value: JSON, node: str) -> JSON:
    details = {"node": node, "rpc": binding.key, "result": value}
    if status == GoalStatus.STATUS_SUCCEEDED:
        return _outcome(binding, value, node)
    if status == GoalStatus.STATUS_CANCELED:
        raise CancelledByRobotError(f"{binding.ros_name}: the goal was cancelled",
                                    hint="the task was stopped before it finished", details=details)
    raise RobotFailure(f"{binding.ros_name}: the goal was aborted", code="aborted",
                       hint="the robot could not finish it; tell the user", details=details)
