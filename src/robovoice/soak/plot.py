"""A tiny PNG line plotter (numpy + zlib + struct; no plotting library is a dependency).

    write_png_plot(path, [("RSS (MIB)", xs, ys), ...], x_label="SIMULATED MINUTES")

Panels stacked vertically, each with its own y range, grid lines, tick labels (a 3x5 pixel
font, upper case, digits and a few signs) and one polyline. Enough to see whether memory is
flat; not a general plotting tool.
"""

from __future__ import annotations

import itertools
import struct
import zlib
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import numpy.typing as npt

_FONT = {  # 3x5 glyphs, rows top to bottom, 3 bits each
    "0": "111101101101111", "1": "010110010010111", "2": "111001111100111", "3": "111001111001111",
    "4": "101101111001001", "5": "111100111001111", "6": "111100111101111", "7": "111001010010010",
    "8": "111101111101111", "9": "111101111001111", ".": "000000000000010", "-": "000000111000000",
    " ": "000000000000000", "%": "101001010100101", "/": "001001010100100", "(": "010100100100010",
    ")": "010001001001010",
    "A": "010101111101101", "B": "110101110101110", "C": "111100100100111", "D": "110101101101110",
    "E": "111100110100111", "F": "111100110100100", "G": "111100101101111", "H": "101101111101101",
    "J": "001001001101111",
    "I": "111010010010111", "K": "101101110101101", "L": "100100100100111", "M": "101111111101101",
    "N": "111101101101101", "O": "111101101101111", "P": "111101111100100", "R": "110101110101101",
    "S": "111100111001111", "T": "111010010010010", "U": "101101101101111", "W": "101101111111101",
    "X": "101101010101101", "Y": "101101010010010", "Z": "111001010100111",
}
Image = npt.NDArray[np.uint8]
_SCALE = 2
_W, _PANEL_H, _LEFT, _RIGHT, _TOP, _BOTTOM = 900, 260, 80, 20, 28, 34


def _text(img: Image, x: int, y: int, text: str, color: tuple[int, int, int] = (0, 0, 0)) -> None:
    for ch in text.upper():
        glyph = _FONT.get(ch, _FONT[" "])
        for i, bit in enumerate(glyph):
            if bit == "1":
                r, c = divmod(i, 3)
                y0, x0 = y + r * _SCALE, x + c * _SCALE
                img[max(0, y0):y0 + _SCALE, max(0, x0):x0 + _SCALE] = color
        x += 4 * _SCALE


def _line(img: Image, x0: float, y0: float, x1: float, y1: float, color: tuple[int, int, int]) -> None:
    steps = int(max(abs(x1 - x0), abs(y1 - y0))) + 1
    xs = np.rint(np.linspace(x0, x1, steps)).astype(int)
    ys = np.rint(np.linspace(y0, y1, steps)).astype(int)
    h, w = img.shape[:2]
    for dx in (0, 1):
        ok = (xs + dx >= 0) & (xs + dx < w) & (ys >= 0) & (ys < h)
        img[ys[ok], xs[ok] + dx] = color


def _fmt(v: float) -> str:
    return f"{v:.0f}" if abs(v) >= 100 else f"{v:.1f}" if abs(v) >= 10 else f"{v:.2f}"


def _panel(img: Image, top: int, title: str, xs: Sequence[float], ys: Sequence[float], x_label: str,
           color: tuple[int, int, int]) -> None:
    x_lo, x_hi = min(xs), max(xs)
    y_lo, y_hi = min(ys), max(ys)
    pad = max((y_hi - y_lo) * 0.1, abs(y_hi) * 0.02, 1e-9)
    y_lo, y_hi = y_lo - pad, y_hi + pad
    x_hi = x_hi if x_hi > x_lo else x_lo + 1
    left, right, y0, y1 = _LEFT, _W - _RIGHT, top + _TOP, top + _PANEL_H - _BOTTOM

    def px(x: float) -> float:
        return left + (x - x_lo) / (x_hi - x_lo) * (right - left)

    def py(y: float) -> float:
        return y1 - (y - y_lo) / (y_hi - y_lo) * (y1 - y0)

    _text(img, left, top + 8, title)
    for i in range(5):  # horizontal grid + y labels
        v = y_lo + (y_hi - y_lo) * i / 4
        y = round(py(v))
        img[y, left:right] = (225, 225, 225)
        _text(img, 4, y - 5, _fmt(v))
    for i in range(7):  # vertical grid + x labels
        v = x_lo + (x_hi - x_lo) * i / 6
        x = round(px(v))
        img[y0:y1, x] = (225, 225, 225)
        label = _fmt(v)
        _text(img, min(x - 8, right - len(label) * 4 * _SCALE), y1 + 6, label)
    _text(img, right - len(x_label) * 4 * _SCALE, y1 + 20, x_label)
    img[y0:y1 + 1, left] = img[y1, left:right] = (0, 0, 0)
    pts = [(px(x), py(y)) for x, y in zip(xs, ys, strict=True)]
    for (ax, ay), (bx, by) in itertools.pairwise(pts):
        _line(img, ax, ay, bx, by, color)
    for fx, fy in pts:
        cx, cy = round(fx), round(fy)
        img[max(0, cy - 1):cy + 2, max(0, cx - 1):cx + 2] = color


def render(panels: Sequence[tuple[str, Sequence[float], Sequence[float]]], x_label: str) -> Image:
    colors = [(31, 119, 180), (214, 39, 40), (44, 160, 44), (148, 103, 189)]
    img = np.full((_PANEL_H * len(panels), _W, 3), 255, dtype=np.uint8)
    for i, (title, xs, ys) in enumerate(panels):
        if len(xs) != len(ys) or not xs:
            raise ValueError(f"panel {title!r}: {len(xs)} x values and {len(ys)} y values (need the same, > 0)")
        _panel(img, i * _PANEL_H, title, xs, ys, x_label, colors[i % len(colors)])
    return img


def encode_png(img: Image) -> bytes:
    """An RGB image (height x width x 3, uint8) as PNG bytes."""
    h, w, _ = img.shape
    raw = b"".join(b"\x00" + img[r].tobytes() for r in range(h))

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def write_png_plot(path: Path, panels: Sequence[tuple[str, Sequence[float], Sequence[float]]],
                   x_label: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(encode_png(render(panels, x_label)))
    return path
