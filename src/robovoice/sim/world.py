"""The simulated home: a flat of 12 x 8 m with named places and a waypoint graph.

Layout (x to the right, y up, metres; the hallway runs along y = 4)::

    y=8 +-----------------------------------------------+  balcony (9.0, 8.7), door closed
        |  kitchen (2.0, 6.5)          living room (9.0, 6.0)
    y=4 |==hallway=================(6.0, 4.0)=========== front door (11.5, 4.0)
        |       charging dock (4.0, 3.2)
        |  bedroom (2.5, 1.5)          bathroom (6.5, 1.5)
    y=0 +-----------------------------------------------+

Every place hangs off the hallway on a short straight spur (its "door" is the point of the
hallway straight above or below it), so a route is: down/up the spur to the hallway, along
the hallway, up/down the target's spur. This keeps distances plausible with no geometry
library. Name lookup is deliberately strict: a few unambiguous aliases ("dock", "lounge")
and spelling variants ("Living Room", "livingroom", "the kitchen"), never a guess.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass

HALLWAY_Y = 4.0
ARRIVAL_TOLERANCE_M = 0.3


@dataclass(frozen=True, slots=True)
class Point:
    x: float
    y: float

    def distance_to(self, other: Point) -> float:
        return math.hypot(other.x - self.x, other.y - self.y)


@dataclass(frozen=True, slots=True)
class Place:
    """A named place. `blocked` says why it cannot be reached (None: reachable)."""

    name: str
    position: Point
    description: str
    blocked: str | None = None
    preposition: str = "in"  # "in the kitchen", "at the front door": how the robot says it is there

    @property
    def reachable(self) -> bool:
        return self.blocked is None

    @property
    def where(self) -> str:
        return f"{self.preposition} the {self.name}"

    @property
    def door(self) -> Point:
        """Where the place's spur meets the hallway."""
        return Point(self.position.x, HALLWAY_Y)


PLACES: tuple[Place, ...] = (
    Place("kitchen", Point(2.0, 6.5), "the kitchen, north-west"),
    Place("living room", Point(9.0, 6.0), "the living room with the sofa, north-east"),
    Place("bedroom", Point(2.5, 1.5), "the bedroom, south-west"),
    Place("bathroom", Point(6.5, 1.5), "the bathroom, south"),
    Place("hallway", Point(6.0, HALLWAY_Y), "the middle of the hallway"),
    Place("front door", Point(11.5, HALLWAY_Y), "the flat's front door, east end of the hallway", preposition="at"),
    Place("charging dock", Point(4.0, 3.2), "the robot's charging dock, off the hallway", preposition="at"),
    Place("balcony", Point(9.0, 8.7), "the balcony beyond the living room",
          blocked="the balcony door is closed", preposition="on"),
)

DOCK = "charging dock"

_BY_NAME: dict[str, Place] = {p.name: p for p in PLACES}

# Unambiguous extra names, already normalised (see `normalise`).
_ALIASES: dict[str, str] = {
    "dock": DOCK,
    "charger": DOCK,
    "charging station": DOCK,
    "docking station": DOCK,
    "home": DOCK,  # "home to the dock with you", "go home": the robot's home is its dock (text test v63)
    "base": DOCK,
    "lounge": "living room",
    "sitting room": "living room",
    "front room": "living room",
    "loo": "bathroom",
    "toilet": "bathroom",
    "lavatory": "bathroom",
    "washroom": "bathroom",
    "restroom": "bathroom",
    "hall": "hallway",
    "lobby": "hallway",  # Scots for the hall of a house (text test v77)
    "corridor": "hallway",
    "entrance": "front door",
    "entrance door": "front door",
    "main door": "front door",
}

_LEADING_WORDS = re.compile(r"^(?:to|the|my|our|your)\s+")


def normalise(text: str) -> str:
    """Lower case, punctuation to spaces, single spaces, no leading "the"/"my"/"to"."""
    text = re.sub(r"[^a-z0-9]+", " ", text.lower()).strip()
    while True:
        stripped = _LEADING_WORDS.sub("", text)
        if stripped == text:
            return text
        text = stripped


def find_place(text: str) -> Place | None:
    """The place `text` names, or None. Matches names, aliases and their spaceless forms, and one
    whose room is said as somebody's ("Abbu's bedroom", text test v110: the home has one bedroom)."""
    key = normalise(text)
    if not key:
        return None
    # (also typed with no apostrophe: "grandmas bedroom", text test v118)
    if (whose := re.match(r"^[a-z]+(?: s|s) (.+)$", key)) is not None and (found := find_place(whose.group(1))):
        return found
    for candidate in (key, key.replace(" ", "")):
        for name, place in _BY_NAME.items():
            if candidate in (name, name.replace(" ", "")):
                return place
        for alias, name in _ALIASES.items():
            if candidate in (alias, alias.replace(" ", "")):
                return _BY_NAME[name]
    return None


def place(name: str) -> Place:
    """The place with this canonical name (raises KeyError: for code, not user input)."""
    return _BY_NAME[name]


def known_places(*, reachable_only: bool = False) -> list[str]:
    return [p.name for p in PLACES if p.reachable or not reachable_only]


def nearest_place(point: Point) -> Place:
    """The reachable place closest to `point` (straight-line distance)."""
    return min((p for p in PLACES if p.reachable), key=lambda p: p.position.distance_to(point))


def place_at(point: Point) -> Place | None:
    """The place the robot is at (within the arrival tolerance), if any."""
    here = nearest_place(point)
    return here if here.position.distance_to(point) <= ARRIVAL_TOLERANCE_M else None


def route(start: Point, goal: Point) -> list[Point]:
    """Waypoints from `start` to `goal` (both included) through the hallway.

    `start` may be anywhere on the network (on the hallway or on a spur, e.g. after a
    cancelled drive). On the same spur the route is a straight line.
    """
    same_spur = math.isclose(start.x, goal.x, abs_tol=1e-6) and (
        (start.y - HALLWAY_Y) * (goal.y - HALLWAY_Y) > 0
    )
    points = [start, goal] if same_spur else [start, Point(start.x, HALLWAY_Y), Point(goal.x, HALLWAY_Y), goal]
    deduplicated = [points[0]]
    for point in points[1:]:
        if point.distance_to(deduplicated[-1]) > 1e-9:
            deduplicated.append(point)
    return deduplicated


def route_length(points: list[Point]) -> float:
    return sum(a.distance_to(b) for a, b in itertools.pairwise(points))


FLAT_WIDTH_M = 12.0
FLAT_DEPTH_M = 8.0


def map_message() -> dict[str, object]:
    """The map as the navigation node publishes it on its ``map`` topic (as a real robot
    publishes its map with named places): the flat's bounds, the drivable ways (the hallway
    and each place's spur) and the places, with their coordinates and whether they can be
    reached. Metres, x to the right, y up."""
    along = [p.position.x for p in PLACES if p.reachable]
    ways = [[[min(along), HALLWAY_Y], [max(along), HALLWAY_Y]]]
    ways += [[[p.door.x, p.door.y], [p.position.x, p.position.y]] for p in PLACES
             if p.reachable and p.position.y != HALLWAY_Y]
    return {
        "frame": "map",
        "bounds": {"min_x": 0.0, "min_y": 0.0, "max_x": FLAT_WIDTH_M, "max_y": FLAT_DEPTH_M},
        "ways": ways,
        "places": [{"name": p.name, "x": p.position.x, "y": p.position.y, "reachable": p.reachable,
                    "blocked": p.blocked, "description": p.description} for p in PLACES],
    }
