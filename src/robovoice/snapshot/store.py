"""Latest-value buffers with staleness: the snapshot node.

`SnapshotStore` subscribes to topics and keeps only the *latest* message of each: a new
message overwrites a slot in place (O(1), constant memory however fast a topic
publishes; no queue). `read` answers at once from that slot, never waiting for the next
message. The age of a value is measured from its *local receive time* on a monotonic
clock, so clock skew between the robot and this machine cannot make data look fresh.

The MCP server tells the store about presence: `publisher_gone(topic)` when the node that
publishes a topic leaves (reads then say so instead of returning its last value), and
`publisher_back(topic)` when it returns.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from robovoice.errors import RobovoiceError
from robovoice.middleware.base import JSON, Message, Middleware, Subscription

Clock = Callable[[], float]


class UntrackedTopicError(RobovoiceError, LookupError):
    """`read` of a topic the store does not track: a programming or configuration error."""


@dataclass(frozen=True, slots=True)
class SnapshotImage:
    """An image value: ``{"mime_type": "image/...", "data": <base64>}``."""

    mime_type: str
    data: str
    """base64, as it travelled on the middleware (not decoded)."""


@dataclass(frozen=True, slots=True)
class Snapshot:
    """The latest value of a topic at the moment of reading.

    `reason` is set exactly when there is nothing to give (then `value` is None): nothing
    received yet, or the publisher has gone.
    `stamp` is the publisher's wall clock (UNIX seconds) as sent; `age_s` is local
    (monotonic) time since this machine received it; `stale` means older than the
    maximum age asked for, or no value at all.
    """

    value: JSON
    stamp: float | None
    age_s: float | None
    stale: bool
    reason: str | None = None
    topic: str = ""

    @property
    def has_value(self) -> bool:
        return self.reason is None

    def image(self) -> SnapshotImage | None:
        """The image carried by the value, when the value is one (see `as_image`)."""
        return as_image(self.value)

    @property
    def is_image(self) -> bool:
        return as_image(self.value) is not None

    def to_dict(self, *, include_value: bool = True) -> dict[str, JSON]:
        """``{value, stamp, age_s, stale}`` plus ``reason`` when set; `include_value=False`
        leaves the value out (for an image sent as image content beside this metadata)."""
        out: dict[str, JSON] = {}
        if include_value:
            out["value"] = self.value
        out["stamp"] = self.stamp
        out["age_s"] = None if self.age_s is None else round(self.age_s, 3)
        out["stale"] = self.stale
        if self.reason is not None:
            out["reason"] = self.reason
        return out


def as_image(value: JSON) -> SnapshotImage | None:
    """`value` as an image if it is ``{"mime_type": "image/...", "data": <str>}`` (other keys,
    e.g. width and height, are allowed), else None."""
    if not isinstance(value, dict):
        return None
    mime = value.get("mime_type")
    data = value.get("data")
    if isinstance(mime, str) and mime.startswith("image/") and isinstance(data, str):
        return SnapshotImage(mime, data)
    return None


class _Slot:
    """One topic's latest message. Mutated in place by the subscription callback."""

    __slots__ = ("gone", "received_at", "stamp", "subscription", "value")

    def __init__(self) -> None:
        self.value: JSON = None
        self.stamp: float | None = None
        self.received_at: float | None = None  # local monotonic time; None: nothing yet
        self.gone = False
        self.subscription: Subscription | None = None


class SnapshotStore:
    """The latest message per tracked topic. Use on one event loop (as the middleware's callbacks are)."""

    def __init__(self, clock: Clock = time.monotonic) -> None:
        self._clock = clock
        self._slots: dict[str, _Slot] = {}

    def topics(self) -> list[str]:
        return sorted(self._slots)

    def is_tracked(self, topic: str) -> bool:
        return topic in self._slots

    async def track(self, middleware: Middleware, topic: str) -> None:
        """Subscribe to `topic` and keep its latest message. Tracking a topic twice is a no-op."""
        if topic in self._slots:
            return
        slot = _Slot()
        self._slots[topic] = slot
        clock = self._clock

        def receive(message: Message) -> None:
            slot.value = message.value
            slot.stamp = message.stamp
            slot.received_at = clock()
            slot.gone = False  # a message is proof its publisher is there

        try:
            slot.subscription = await middleware.subscribe(topic, receive)
        except BaseException:
            if self._slots.get(topic) is slot:
                del self._slots[topic]
            raise

    def untrack(self, topic: str) -> None:
        """Stop tracking `topic` and forget its value. Unknown topics are ignored."""
        slot = self._slots.pop(topic, None)
        if slot is not None and slot.subscription is not None:
            slot.subscription.close()

    def close(self) -> None:
        """Untrack every topic."""
        for topic in list(self._slots):
            self.untrack(topic)

    def publisher_gone(self, topic: str) -> None:
        """The publisher of `topic` left: forget the last value; reads say it has gone."""
        slot = self._slots.get(topic)
        if slot is not None:
            slot.gone = True
            slot.value = None
            slot.stamp = None
            slot.received_at = None

    def publisher_back(self, topic: str) -> None:
        """The publisher of `topic` is back: reads wait for (not on) its next message."""
        slot = self._slots.get(topic)
        if slot is not None:
            slot.gone = False

    def read(self, topic: str, max_age_s: float) -> Snapshot:
        """The latest value of `topic` now, flagged stale past `max_age_s`. Never waits.
        Raises `UntrackedTopicError` for a topic that was never tracked."""
        slot = self._slots.get(topic)
        if slot is None:
            tracked = ", ".join(repr(t) for t in sorted(self._slots)) or "none"
            raise UntrackedTopicError(f"topic {topic!r} is not tracked (tracked: {tracked})")
        if slot.gone:
            return Snapshot(None, None, None, True, f"the publisher of {topic!r} has gone", topic)
        if slot.received_at is None:
            return Snapshot(None, None, None, True, f"no message received yet on {topic!r}", topic)
        age = max(0.0, self._clock() - slot.received_at)
        return Snapshot(slot.value, slot.stamp, age, age > max_age_s, None, topic)
