"""What the sim camera sees: a small gray picture of the place the robot is near.

A frame is a wall whose shade depends on the place, a floor, a dark doorway whose position
follows the robot's heading, and a sign with the place's name in capitals (a 5 x 7 pixel
font drawn at twice the size), so a vision model can read where the robot is. Shapes are
aligned to the JPEG's 8 x 8 blocks where they can be, which keeps encoding fast.
"""

from __future__ import annotations

from dataclasses import dataclass

from robovoice.sim.jpeg import encode_gray

WIDTH = 160
HEIGHT = 120
HEADING_BUCKETS = 8

_FONT_ROWS = 7
_FONT_COLS = 5
_GLYPHS: dict[str, str] = {
    "A": ".###./#...#/#...#/#####/#...#/#...#/#...#",
    "B": "####./#...#/#...#/####./#...#/#...#/####.",
    "C": ".###./#...#/#..../#..../#..../#...#/.###.",
    "D": "####./#...#/#...#/#...#/#...#/#...#/####.",
    "E": "#####/#..../#..../####./#..../#..../#####",
    "F": "#####/#..../#..../####./#..../#..../#....",
    "G": ".###./#...#/#..../#.###/#...#/#...#/.####",
    "H": "#...#/#...#/#...#/#####/#...#/#...#/#...#",
    "I": ".###./..#../..#../..#../..#../..#../.###.",
    "J": "..###/...#./...#./...#./...#./#..#./.##..",
    "K": "#...#/#..#./#.#../##.../#.#../#..#./#...#",
    "L": "#..../#..../#..../#..../#..../#..../#####",
    "M": "#...#/##.##/#.#.#/#.#.#/#...#/#...#/#...#",
    "N": "#...#/#...#/##..#/#.#.#/#..##/#...#/#...#",
    "O": ".###./#...#/#...#/#...#/#...#/#...#/.###.",
    "P": "####./#...#/#...#/####./#..../#..../#....",
    "Q": ".###./#...#/#...#/#...#/#.#.#/#..#./.##.#",
    "R": "####./#...#/#...#/####./#.#../#..#./#...#",
    "S": ".####/#..../#..../.###./....#/....#/####.",
    "T": "#####/..#../..#../..#../..#../..#../..#..",
    "U": "#...#/#...#/#...#/#...#/#...#/#...#/.###.",
    "V": "#...#/#...#/#...#/#...#/#...#/.#.#./..#..",
    "W": "#...#/#...#/#...#/#.#.#/#.#.#/#.#.#/.#.#.",
    "X": "#...#/#...#/.#.#./..#../.#.#./#...#/#...#",
    "Y": "#...#/#...#/.#.#./..#../..#../..#../..#..",
    "Z": "#####/....#/...#./..#../.#.../#..../#####",
    " ": "...../...../...../...../...../...../.....",
}

_WALL_SHADES: dict[str, int] = {
    "kitchen": 200,
    "living room": 176,
    "bedroom": 144,
    "bathroom": 224,
    "hallway": 184,
    "front door": 160,
    "charging dock": 152,
}


@dataclass(frozen=True, slots=True)
class View:
    """What determines a frame: the place in sight and the heading, in 45 degree steps."""

    place: str
    heading_bucket: int

    @classmethod
    def of(cls, place: str, heading_deg: float) -> View:
        step = 360 / HEADING_BUCKETS
        return cls(place, round((heading_deg % 360) / step) % HEADING_BUCKETS)


class _Canvas:
    def __init__(self, width: int, height: int, fill: int) -> None:
        self.width = width
        self.height = height
        self.pixels = bytearray([fill]) * (width * height)

    def rect(self, left: int, top: int, width: int, height: int, shade: int) -> None:
        left, right = max(0, left), min(self.width, left + width)
        for y in range(max(0, top), min(self.height, top + height)):
            row = y * self.width
            self.pixels[row + left:row + right] = bytes([shade]) * max(0, right - left)

    def text(self, text: str, left: int, top: int, scale: int, shade: int) -> None:
        for index, char in enumerate(text):
            rows = _GLYPHS.get(char, _GLYPHS[" "]).split("/")
            origin = left + index * (_FONT_COLS + 1) * scale
            for r, row in enumerate(rows):
                for c, cell in enumerate(row):
                    if cell == "#":
                        self.rect(origin + c * scale, top + r * scale, scale, scale, shade)


def text_width(text: str, scale: int) -> int:
    return max(0, len(text) * (_FONT_COLS + 1) * scale - scale)


def render(view: View) -> bytes:
    """The gray pixels (row-major, WIDTH x HEIGHT) of `view`."""
    wall = _WALL_SHADES.get(view.place, 168)
    canvas = _Canvas(WIDTH, HEIGHT, wall)
    for band in range(0, 80, 8):  # the wall darkens a little towards the floor
        canvas.rect(0, band, WIDTH, 8, max(0, wall - band // 2))
    for band in range(80, HEIGHT, 8):  # the floor lightens towards the robot
        canvas.rect(0, band, WIDTH, 8, 72 + (band - 80))
    doorway_left = (view.heading_bucket * WIDTH // HEADING_BUCKETS + 8) % WIDTH
    canvas.rect(doorway_left, 8, 24, 72, 48)
    label = view.place.upper()
    scale = 2 if text_width(label, 2) <= WIDTH - 8 else 1
    width = text_width(label, scale)
    left = (WIDTH - width) // 2
    canvas.rect(left - 4, 24, width + 8, _FONT_ROWS * scale + 8, 240)
    canvas.text(label, left, 28, scale, 16)
    return bytes(canvas.pixels)


def render_jpeg(view: View, *, quality: int = 75) -> bytes:
    """`view` as a baseline JPEG file."""
    return encode_gray(render(view), WIDTH, HEIGHT, quality=quality)
