"""The sim clock and the map of the home."""

from __future__ import annotations

import itertools
import time

import pytest

from robovoice.sim import world
from robovoice.sim.clock import SimClock


async def test_clock_runs_faster_than_real_time() -> None:
    clock = SimClock(speed=50)
    real_start, sim_start = time.monotonic(), clock.now()
    await clock.sleep(2.0)  # 40 ms real
    sim_elapsed = clock.now() - sim_start
    real_elapsed = time.monotonic() - real_start
    assert sim_elapsed >= 2.0
    assert real_elapsed < 1.0
    assert clock.to_real(5.0) == pytest.approx(0.1)


async def test_ticks_follow_a_fixed_schedule() -> None:
    clock = SimClock(speed=10)
    stamps = []
    async for now in clock.ticks(0.5):
        stamps.append(now)
        if len(stamps) == 9:
            break
    span = stamps[-1] - stamps[0]
    assert span == pytest.approx(4.0, abs=0.5)
    assert all(b > a for a, b in itertools.pairwise(stamps))


def test_clock_rejects_a_bad_speed() -> None:
    with pytest.raises(ValueError, match="positive"):
        SimClock(speed=0)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("kitchen", "kitchen"),
        ("the kitchen", "kitchen"),
        ("  The Kitchen. ", "kitchen"),
        ("Living Room", "living room"),
        ("livingroom", "living room"),
        ("living-room", "living room"),
        ("dock", "charging dock"),
        ("the charging dock", "charging dock"),
        ("charger", "charging dock"),
        ("Front Door", "front door"),
        ("hall", "hallway"),
        ("the lobby", "hallway"),  # Scots for the hall of a house (text test v77)
        ("BATHROOM", "bathroom"),
        ("the front room", "living room"),  # everyday British names
        ("the loo", "bathroom"),
        ("toilet", "bathroom"),
        ("balcony", "balcony"),
        ("home", "charging dock"),  # the robot's home is its dock (text test v63: "home to the dock with you")
        ("base", "charging dock"),
        ("Abbu's bedroom", "bedroom"), ("Granny's kitchen", "kitchen"),  # the home's one room (text test v110)
        ("grandmas bedroom", "bedroom"), ("dads kitchen", "kitchen"),  # typed with no apostrophe (text test v118)
    ],
)
def test_place_names_are_normalised(text: str, expected: str) -> None:
    place = world.find_place(text)
    assert place is not None
    assert place.name == expected


@pytest.mark.parametrize("text", ["garage", "", "the", "kitchen sink", "room", "door", "cellar", "bed", "Ben's room",
                                  "bens room", "bathrooms", "Anna's garage"])
def test_unknown_places_are_never_invented(text: str) -> None:
    assert world.find_place(text) is None


def test_the_map() -> None:
    reachable = world.known_places(reachable_only=True)
    assert reachable == ["kitchen", "living room", "bedroom", "bathroom", "hallway", "front door",
                         "charging dock"]
    assert world.place("balcony").blocked == "the balcony door is closed"
    for p in world.PLACES:  # the flat is about 12 x 8 m; the balcony is just outside
        assert 0 <= p.position.x <= 12
        assert 0 <= p.position.y <= (9 if p.name == "balcony" else 8)
    kitchen, living = world.place("kitchen").position, world.place("living room").position
    path = world.route(kitchen, living)
    assert path[0] == kitchen and path[-1] == living
    assert all(pt.y == world.HALLWAY_Y for pt in path[1:-1])  # through the hallway
    assert world.route_length(path) == pytest.approx(2.5 + 7.0 + 2.0)
    # the same spur: straight there, not via the hallway
    halfway = world.Point(kitchen.x, 5.0)
    assert world.route(halfway, kitchen) == [halfway, kitchen]


def test_nearest_place_and_place_at() -> None:
    assert world.nearest_place(world.Point(2.2, 6.0)).name == "kitchen"
    assert world.nearest_place(world.Point(9.0, 8.6)).name != "balcony"  # never somewhere unreachable
    assert world.place_at(world.place("bedroom").position) == world.place("bedroom")
    assert world.place_at(world.Point(8.0, 4.0)) is None
