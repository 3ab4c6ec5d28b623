"""A topic subscription of the Zenoh adapter: samples decoded into `Message`s on the event loop."""

from __future__ import annotations

import logging
import time
from collections.abc import Callable

import zenoh

from robovoice.middleware.base import Message
from robovoice.middleware.zenoh_bridge import undeclare
from robovoice.middleware.zenoh_codec import decode, decode_object

log = logging.getLogger(__name__)


class TopicSubscription:
    """A `subscribe()` handle."""

    def __init__(self, registry: set[TopicSubscription], topic: str, callback: Callable[[Message], None]) -> None:
        self._registry = registry  # the adapter's open subscriptions
        self._topic = topic
        self._callback = callback
        self._subscriber: zenoh.Subscriber[None] | None = None
        self.closed = False

    def deliver(self, sample: zenoh.Sample) -> None:
        if self.closed:
            return
        try:
            value = decode(sample.payload.to_bytes())
        except ValueError as exc:
            log.warning("topic %s: dropped a message that is not JSON (%s)", self._topic, exc)
            return
        stamp = decode_object(None if sample.attachment is None else sample.attachment.to_bytes()).get("stamp")
        message = Message(self._topic, value, float(stamp) if isinstance(stamp, int | float) else time.time())
        try:
            self._callback(message)
        except Exception:  # a subscriber's bug must not break delivery
            log.exception("subscriber of %s failed", self._topic)

    def close(self) -> None:
        if self.closed:
            return
        self.closed = True
        if self._subscriber is not None:
            undeclare(self._subscriber)
        self._registry.discard(self)
