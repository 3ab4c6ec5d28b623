"""The camera's JPEGs are real JPEGs."""

from __future__ import annotations

import base64
import subprocess
from pathlib import Path

import pytest

from robovoice.sim import frames, jpeg


def _gradient(width: int, height: int) -> bytes:
    return bytes((x * 255 // width + y) % 256 for y in range(height) for x in range(width))


def test_jpeg_structure() -> None:
    data = jpeg.encode_gray(_gradient(40, 24), 40, 24)
    assert data[:2] == b"\xff\xd8" and data[-2:] == b"\xff\xd9"
    sof = data.index(b"\xff\xc0")
    assert data[sof + 5:sof + 9] == b"\x00\x18\x00\x28"  # height 24, width 40
    for marker in (b"\xff\xdb", b"\xff\xc4", b"\xff\xda", b"JFIF\x00"):
        assert marker in data


def test_bad_input_is_refused() -> None:
    with pytest.raises(ValueError, match="pixels"):
        jpeg.encode_gray(b"\x00" * 10, 4, 4)
    with pytest.raises(ValueError, match="quality"):
        jpeg.quant_table(0)


def _decode(djpeg: str, path: Path) -> tuple[int, int, bytes]:
    out = subprocess.run([djpeg, "-pnm", str(path)], capture_output=True, check=True).stdout
    magic, size, maxval, pixels = out.split(b"\n", 3)
    assert magic == b"P5" and maxval == b"255"  # one gray channel
    width, height = map(int, size.split())
    return width, height, pixels


@pytest.mark.parametrize(("width", "height"), [(160, 120), (37, 21)])
def test_djpeg_decodes_what_we_encode(djpeg: str, tmp_path: Path, width: int, height: int) -> None:
    pixels = _gradient(width, height)
    path = tmp_path / "frame.jpg"
    path.write_bytes(jpeg.encode_gray(pixels, width, height, quality=90))
    got_w, got_h, decoded = _decode(djpeg, path)
    assert (got_w, got_h) == (width, height)
    mean_error = sum(abs(a - b) for a, b in zip(decoded, pixels, strict=True)) / len(pixels)
    assert mean_error < 4


def test_camera_frames_decode_and_follow_the_view(djpeg: str, tmp_path: Path) -> None:
    kitchen = frames.render_jpeg(frames.View.of("kitchen", 90))
    kitchen_west = frames.render_jpeg(frames.View.of("kitchen", 180))
    bedroom = frames.render_jpeg(frames.View.of("bedroom", 90))
    assert len({kitchen, kitchen_west, bedroom}) == 3
    path = tmp_path / "kitchen.jpg"
    path.write_bytes(kitchen)
    width, height, decoded = _decode(djpeg, path)
    assert (width, height) == (frames.WIDTH, frames.HEIGHT)
    # the sign with the name is light, its letters dark: both shades are in the picture
    sign_rows = decoded[28 * width:42 * width]
    assert max(sign_rows) > 200 and min(sign_rows) < 60
    assert base64.b64decode(base64.b64encode(kitchen)) == kitchen


def test_views_quantise_the_heading() -> None:
    assert frames.View.of("kitchen", 1.0) == frames.View.of("kitchen", 359.0)
    assert frames.View.of("kitchen", 90.0).heading_bucket == 2
