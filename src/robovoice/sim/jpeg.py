"""A tiny baseline JPEG encoder for grayscale images, in pure Python.

The sim camera needs small real JPEGs and the core install has no imaging library, so
this encodes one 8-bit luminance channel as baseline sequential JPEG (SOF0) with the
standard (ITU T.81 Annex K) quantisation and Huffman tables. Any decoder reads it.
Speed: blocks of one flat value skip the DCT, so a 160 x 120 frame of mostly flat
shapes encodes in a few milliseconds; a busy frame takes a few tens.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Sequence
from functools import cache

# Zig-zag order: position k of the coded sequence -> index (row * 8 + col) in the block.
ZIGZAG: tuple[int, ...] = (
    0, 1, 8, 16, 9, 2, 3, 10, 17, 24, 32, 25, 18, 11, 4, 5,
    12, 19, 26, 33, 40, 48, 41, 34, 27, 20, 13, 6, 7, 14, 21, 28,
    35, 42, 49, 56, 57, 50, 43, 36, 29, 22, 15, 23, 30, 37, 44, 51,
    58, 59, 52, 45, 38, 31, 39, 46, 53, 60, 61, 54, 47, 55, 62, 63,
)

_LUMA_QUANT: tuple[int, ...] = (  # natural (row-major) order, Annex K.1
    16, 11, 10, 16, 24, 40, 51, 61,
    12, 12, 14, 19, 26, 58, 60, 55,
    14, 13, 16, 24, 40, 57, 69, 56,
    14, 17, 22, 29, 51, 87, 80, 62,
    18, 22, 37, 56, 68, 109, 103, 77,
    24, 35, 55, 64, 81, 104, 113, 92,
    49, 64, 78, 87, 103, 121, 120, 101,
    72, 92, 95, 98, 112, 100, 103, 99,
)

_DC_BITS = (0, 1, 5, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0)
_DC_VALUES = tuple(range(12))
_AC_BITS = (0, 2, 1, 3, 3, 2, 4, 3, 5, 5, 4, 4, 0, 0, 1, 0x7D)
_AC_VALUES = (
    0x01, 0x02, 0x03, 0x00, 0x04, 0x11, 0x05, 0x12, 0x21, 0x31, 0x41, 0x06, 0x13, 0x51, 0x61, 0x07,
    0x22, 0x71, 0x14, 0x32, 0x81, 0x91, 0xA1, 0x08, 0x23, 0x42, 0xB1, 0xC1, 0x15, 0x52, 0xD1, 0xF0,
    0x24, 0x33, 0x62, 0x72, 0x82, 0x09, 0x0A, 0x16, 0x17, 0x18, 0x19, 0x1A, 0x25, 0x26, 0x27, 0x28,
    0x29, 0x2A, 0x34, 0x35, 0x36, 0x37, 0x38, 0x39, 0x3A, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48, 0x49,
    0x4A, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58, 0x59, 0x5A, 0x63, 0x64, 0x65, 0x66, 0x67, 0x68, 0x69,
    0x6A, 0x73, 0x74, 0x75, 0x76, 0x77, 0x78, 0x79, 0x7A, 0x83, 0x84, 0x85, 0x86, 0x87, 0x88, 0x89,
    0x8A, 0x92, 0x93, 0x94, 0x95, 0x96, 0x97, 0x98, 0x99, 0x9A, 0xA2, 0xA3, 0xA4, 0xA5, 0xA6, 0xA7,
    0xA8, 0xA9, 0xAA, 0xB2, 0xB3, 0xB4, 0xB5, 0xB6, 0xB7, 0xB8, 0xB9, 0xBA, 0xC2, 0xC3, 0xC4, 0xC5,
    0xC6, 0xC7, 0xC8, 0xC9, 0xCA, 0xD2, 0xD3, 0xD4, 0xD5, 0xD6, 0xD7, 0xD8, 0xD9, 0xDA, 0xE1, 0xE2,
    0xE3, 0xE4, 0xE5, 0xE6, 0xE7, 0xE8, 0xE9, 0xEA, 0xF1, 0xF2, 0xF3, 0xF4, 0xF5, 0xF6, 0xF7, 0xF8,
    0xF9, 0xFA,
)

# DCT basis: _COS[u][x] = C(u)/2 * cos((2x + 1) u pi / 16), so F = M f M^T.
_COS: tuple[tuple[float, ...], ...] = tuple(
    tuple((math.sqrt(0.5) if u == 0 else 1.0) / 2 * math.cos((2 * x + 1) * u * math.pi / 16)
          for x in range(8))
    for u in range(8)
)

Code = tuple[int, int]  # (bits, length)


def _huffman_codes(bits: Sequence[int], values: Sequence[int]) -> dict[int, Code]:
    """Canonical Huffman codes from the counts per code length (T.81 Annex C)."""
    codes: dict[int, Code] = {}
    code = 0
    index = 0
    for length, count in enumerate(bits, start=1):
        for _ in range(count):
            codes[values[index]] = (code, length)
            code += 1
            index += 1
        code <<= 1
    return codes


_DC_CODES = _huffman_codes(_DC_BITS, _DC_VALUES)
_AC_CODES = _huffman_codes(_AC_BITS, _AC_VALUES)


@cache
def quant_table(quality: int) -> tuple[int, ...]:
    """The luminance table scaled for `quality` (1..100) the way libjpeg does."""
    if not 1 <= quality <= 100:
        raise ValueError(f"JPEG quality must be 1..100, got {quality}")
    scale = 5000 // quality if quality < 50 else 200 - 2 * quality
    return tuple(min(255, max(1, (q * scale + 50) // 100)) for q in _LUMA_QUANT)


class _BitWriter:
    def __init__(self) -> None:
        self.out = bytearray()
        self._acc = 0
        self._count = 0

    def write(self, bits: int, length: int) -> None:
        self._acc = (self._acc << length) | (bits & ((1 << length) - 1))
        self._count += length
        while self._count >= 8:
            self._count -= 8
            byte = (self._acc >> self._count) & 0xFF
            self.out.append(byte)
            if byte == 0xFF:
                self.out.append(0x00)  # byte stuffing
        self._acc &= (1 << self._count) - 1

    def flush(self) -> bytes:
        if self._count:
            self.write((1 << (8 - self._count)) - 1, 8 - self._count)  # pad with 1 bits
        return bytes(self.out)


def _magnitude(value: int) -> Code:
    """(extra bits, category) of a DC difference or AC coefficient."""
    size = abs(value).bit_length()
    return (value if value >= 0 else value + (1 << size) - 1), size


def _forward_dct(block: list[float]) -> list[float]:
    rows = [
        [sum(c * v for c, v in zip(basis, block[r * 8:r * 8 + 8], strict=True)) for basis in _COS]
        for r in range(8)
    ]
    out = [0.0] * 64
    for v_index, basis in enumerate(_COS):
        for col in range(8):
            out[v_index * 8 + col] = sum(basis[r] * rows[r][col] for r in range(8))
    return out


def _encode_block(coefficients: list[int], previous_dc: int, writer: _BitWriter) -> int:
    """Huffman-code one quantised block in zig-zag order; returns its DC value."""
    dc = coefficients[0]
    bits, size = _magnitude(dc - previous_dc)
    writer.write(*_DC_CODES[size])
    if size:
        writer.write(bits, size)
    run = 0
    for k in range(1, 64):
        value = coefficients[ZIGZAG[k]]
        if value == 0:
            run += 1
            continue
        while run > 15:
            writer.write(*_AC_CODES[0xF0])  # sixteen zeros
            run -= 16
        bits, size = _magnitude(value)
        writer.write(*_AC_CODES[(run << 4) | size])
        writer.write(bits, size)
        run = 0
    if run:
        writer.write(*_AC_CODES[0x00])  # end of block
    return dc


def _segment(marker: int, payload: bytes) -> bytes:
    return struct.pack(">HH", marker, len(payload) + 2) + payload


def _dht(table_class_id: int, bits: Sequence[int], values: Sequence[int]) -> bytes:
    return _segment(0xFFC4, bytes([table_class_id, *bits, *values]))


def encode_gray(pixels: bytes | bytearray, width: int, height: int, *, quality: int = 75) -> bytes:
    """Encode `width * height` 8-bit gray pixels (row-major) as a baseline JPEG file."""
    if width <= 0 or height <= 0 or width > 0xFFFF or height > 0xFFFF:
        raise ValueError(f"bad JPEG size {width}x{height}")
    if len(pixels) != width * height:
        raise ValueError(f"expected {width * height} pixels, got {len(pixels)}")
    quant = quant_table(quality)
    writer = _BitWriter()
    previous_dc = 0
    for top in range(0, height, 8):
        for left in range(0, width, 8):
            block = [
                float(pixels[min(top + r, height - 1) * width + min(left + c, width - 1)] - 128)
                for r in range(8)
                for c in range(8)
            ]
            if all(v == block[0] for v in block):  # flat: only the DC term is non-zero
                coefficients = [round(block[0] * 8 / quant[0])] + [0] * 63
            else:
                dct = _forward_dct(block)
                coefficients = [round(f / q) for f, q in zip(dct, quant, strict=True)]
            previous_dc = _encode_block(coefficients, previous_dc, writer)
    header = b"".join((
        b"\xff\xd8",
        _segment(0xFFE0, b"JFIF\x00\x01\x01\x00\x00\x01\x00\x01\x00\x00"),
        _segment(0xFFDB, bytes([0x00, *(quant[i] for i in ZIGZAG)])),
        _segment(0xFFC0, struct.pack(">BHHB", 8, height, width, 1) + bytes([1, 0x11, 0])),
        _dht(0x00, _DC_BITS, _DC_VALUES),
        _dht(0x10, _AC_BITS, _AC_VALUES),
        _segment(0xFFDA, bytes([1, 1, 0x00, 0, 63, 0])),
    ))
    return header + writer.flush() + b"\xff\xd9"
