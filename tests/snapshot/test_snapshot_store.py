"""`SnapshotStore`: latest value per topic, staleness from local receive time, presence."""

from __future__ import annotations

import tracemalloc

import pytest

from robovoice.middleware.base import Message, NodeInfo
from robovoice.middleware.memory import MemoryMiddleware
from robovoice.snapshot import Snapshot, SnapshotImage, SnapshotStore, UntrackedTopicError, as_image


class FakeClock:
    def __init__(self, now: float = 1000.0) -> None:
        self.now = now

    def __call__(self) -> float:
        return self.now


class FakeSubscription:
    def __init__(self) -> None:
        self.closed = False

    def close(self) -> None:
        self.closed = True


class FakeBus:
    """Just enough of the Middleware to hand the store's callbacks to the test."""

    def __init__(self) -> None:
        self.callbacks: dict[str, object] = {}
        self.subscriptions: dict[str, FakeSubscription] = {}

    async def subscribe(self, topic: str, callback: object) -> FakeSubscription:
        self.callbacks[topic] = callback
        self.subscriptions[topic] = FakeSubscription()
        return self.subscriptions[topic]

    def publish(self, topic: str, value: object, stamp: float = 0.0) -> None:
        callback = self.callbacks[topic]
        assert callable(callback)
        callback(Message(topic, value, stamp))


@pytest.fixture
def clock() -> FakeClock:
    return FakeClock()


@pytest.fixture
async def tracked(clock: FakeClock) -> tuple[SnapshotStore, FakeBus]:
    store = SnapshotStore(clock=clock)
    bus = FakeBus()
    await store.track(bus, "battery")  # type: ignore[arg-type]  # a fake with only `subscribe`
    return store, bus


def test_untracked_topic_raises(clock: FakeClock) -> None:
    with pytest.raises(UntrackedTopicError, match="'battery' is not tracked"):
        SnapshotStore(clock=clock).read("battery", 5.0)


async def test_never_received(tracked: tuple[SnapshotStore, FakeBus]) -> None:
    store, _ = tracked
    snap = store.read("battery", 5.0)
    assert snap == Snapshot(None, None, None, True, "no message received yet on 'battery'", "battery")
    assert not snap.has_value
    assert snap.to_dict() == {"value": None, "stamp": None, "age_s": None, "stale": True,
                              "reason": "no message received yet on 'battery'"}


async def test_fresh_then_stale(tracked: tuple[SnapshotStore, FakeBus], clock: FakeClock) -> None:
    store, bus = tracked
    bus.publish("battery", {"percent": 80, "charging": False}, stamp=1_700_000_000.0)
    clock.now += 0.25
    snap = store.read("battery", 5.0)
    assert snap.value == {"percent": 80, "charging": False}
    assert snap.stamp == 1_700_000_000.0
    assert snap.age_s == pytest.approx(0.25)
    assert not snap.stale and snap.has_value and snap.reason is None
    assert snap.to_dict() == {"value": {"percent": 80, "charging": False}, "stamp": 1_700_000_000.0,
                              "age_s": 0.25, "stale": False}
    clock.now += 5.0
    later = store.read("battery", 5.0)
    assert later.stale and later.value == {"percent": 80, "charging": False}
    assert later.age_s == pytest.approx(5.25)
    assert not store.read("battery", 10.0).stale  # the max age is the reader's


async def test_age_ignores_the_publishers_clock(tracked: tuple[SnapshotStore, FakeBus]) -> None:
    store, bus = tracked
    bus.publish("battery", 1, stamp=0.0)  # a publisher whose wall clock is decades off
    assert store.read("battery", 1.0).age_s == 0.0
    assert not store.read("battery", 1.0).stale


async def test_publisher_gone_and_back(tracked: tuple[SnapshotStore, FakeBus], clock: FakeClock) -> None:
    store, bus = tracked
    bus.publish("battery", {"percent": 50})
    store.publisher_gone("battery")
    gone = store.read("battery", 5.0)
    assert gone.value is None and gone.stale
    assert gone.reason == "the publisher of 'battery' has gone"
    assert gone.to_dict()["reason"] == "the publisher of 'battery' has gone"
    store.publisher_back("battery")
    back = store.read("battery", 5.0)
    assert back.value is None and back.reason == "no message received yet on 'battery'"
    bus.publish("battery", {"percent": 49})
    assert store.read("battery", 5.0).value == {"percent": 49}


async def test_message_proves_the_publisher_is_there(tracked: tuple[SnapshotStore, FakeBus]) -> None:
    store, bus = tracked
    store.publisher_gone("battery")
    bus.publish("battery", 7)
    assert store.read("battery", 5.0).value == 7


async def test_presence_calls_for_unknown_topics_are_ignored(clock: FakeClock) -> None:
    store = SnapshotStore(clock=clock)
    store.publisher_gone("nope")
    store.publisher_back("nope")
    store.untrack("nope")


async def test_many_messages_keep_one_value(tracked: tuple[SnapshotStore, FakeBus], clock: FakeClock) -> None:
    store, bus = tracked
    def burst(start: int, count: int) -> None:
        for i in range(start, start + count):
            clock.now += 0.001
            bus.publish("battery", {"percent": i % 100, "seq": i})

    burst(0, 100)  # warm up
    tracemalloc.start()
    try:
        before, _ = tracemalloc.get_traced_memory()
        burst(100, 10_000)
        after, _ = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert after - before < 4_096, "memory grew with the number of messages"  # 10 000 dicts: > 1 MB
    snap = store.read("battery", 1.0)
    assert snap.value == {"percent": 10_099 % 100, "seq": 10_099}
    assert snap.age_s == 0.0
    assert store.topics() == ["battery"]


async def test_untrack_closes_the_subscription(tracked: tuple[SnapshotStore, FakeBus]) -> None:
    store, bus = tracked
    store.untrack("battery")
    assert bus.subscriptions["battery"].closed
    assert not store.is_tracked("battery")
    with pytest.raises(UntrackedTopicError):
        store.read("battery", 1.0)


async def test_track_twice_subscribes_once(tracked: tuple[SnapshotStore, FakeBus]) -> None:
    store, bus = tracked
    first = bus.subscriptions["battery"]
    await store.track(bus, "battery")  # type: ignore[arg-type]  # a fake bus: only the subscribe() track uses
    assert bus.subscriptions["battery"] is first


async def test_failed_subscribe_leaves_nothing(clock: FakeClock) -> None:
    class Broken:
        async def subscribe(self, topic: str, callback: object) -> FakeSubscription:
            raise RuntimeError("no route")

    store = SnapshotStore(clock=clock)
    with pytest.raises(RuntimeError):
        await store.track(Broken(), "pose")  # type: ignore[arg-type]  # a bus whose subscribe() fails, nothing else
    assert not store.is_tracked("pose")


async def test_image_detection(clock: FakeClock) -> None:
    store = SnapshotStore(clock=clock)
    bus = FakeBus()
    await store.track(bus, "camera")  # type: ignore[arg-type]  # a fake bus: only the subscribe() track uses
    bus.publish("camera", {"mime_type": "image/jpeg", "data": "/9j/4AAQ", "width": 64})
    snap = store.read("camera", 1.0)
    assert snap.is_image
    assert snap.image() == SnapshotImage("image/jpeg", "/9j/4AAQ")
    meta = snap.to_dict(include_value=False)
    assert "value" not in meta and meta["stale"] is False


@pytest.mark.parametrize(
    "value",
    [
        {"mime_type": "text/plain", "data": "aGk="},
        {"mime_type": "image/png"},
        {"mime_type": "image/png", "data": 5},
        ["image/png", "aGk="],
        "image/png",
        None,
    ],
)
def test_not_images(value: object) -> None:
    assert as_image(value) is None
    assert not Snapshot(value, 0.0, 0.0, False).is_image


async def test_track_with_the_memory_middleware(clock: FakeClock) -> None:
    bus = MemoryMiddleware()
    await bus.start()
    node = await bus.host(NodeInfo("base", topics=("battery",)), {}, {})
    store = SnapshotStore(clock=clock)
    await store.track(bus, "battery")
    assert store.read("battery", 2.0).reason == "no message received yet on 'battery'"
    node.publish("battery", {"percent": 93, "charging": True}, stamp=123.0)
    clock.now += 1.0
    snap = store.read("battery", 2.0)
    assert (snap.value, snap.stamp, snap.age_s, snap.stale) == ({"percent": 93, "charging": True}, 123.0, 1.0,
                                                                False)
    for i in range(100):
        node.publish("battery", {"percent": i, "charging": False})
    assert store.read("battery", 2.0).value == {"percent": 99, "charging": False}
    store.untrack("battery")
    node.publish("battery", {"percent": 1, "charging": False})  # no subscriber left: no error
    await bus.close()
