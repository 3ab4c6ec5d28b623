"""Fuzzing the parsers of what users and other machines hand us: manifests, robot addresses and
``zenoh://`` URIs, config files, WAV headers. Each either gives its value or raises its
documented error with a message — never another exception, never a hang."""

from __future__ import annotations

import contextlib
import io
import json
import struct
import tempfile
import wave
from pathlib import Path
from typing import Any

import numpy as np
from hypothesis import example, given
from hypothesis import strategies as st

from robovoice.address import parse_robot_address
from robovoice.config import Config, load_config
from robovoice.errors import AudioError, ConfigError, ManifestError, MissingDependencyError
from robovoice.manifest import load_manifest_dir
from robovoice.manifest.loader import parse_manifest, validate_manifest
from robovoice.middleware import check_middleware_uri
from robovoice.middleware.zenoh_config import ZenohSettings

from .fuzzkit import JSON_VALUES, SCALARS, bounded

# --- manifests ------------------------------------------------------------------------------

NAMES = st.sampled_from(["navigate_to", "get_pose", "x", "", "bad name!", "a" * 70, "get_battery_state"])
SCHEMAS = st.one_of(
    JSON_VALUES,
    st.fixed_dictionaries({"type": st.sampled_from(["object", "string", "array", 3, None])},
                          optional={"properties": st.dictionaries(st.text(max_size=8), JSON_VALUES, max_size=3),
                                    "required": st.lists(st.text(max_size=8) | SCALARS, max_size=3),
                                    "additionalProperties": st.booleans() | JSON_VALUES}),
)
TOOLS = st.fixed_dictionaries(
    {},
    optional={"name": NAMES | SCALARS, "rpc": st.sampled_from(["drive_to", ""]) | SCALARS,
              "description": st.text(max_size=20) | SCALARS, "parameters": SCHEMAS, "defaults": JSON_VALUES,
              "annotations": JSON_VALUES, "timeout_s": SCALARS, "voice": JSON_VALUES, "for_model": SCALARS,
              "ros2": JSON_VALUES, "kind": SCALARS, "x-extra": JSON_VALUES},
)
SNAPSHOTS = st.fixed_dictionaries(
    {}, optional={"name": NAMES | SCALARS, "topic": st.text(max_size=12) | SCALARS, "description": SCALARS,
                  "max_age_s": SCALARS, "voice": JSON_VALUES, "for_model": SCALARS, "ros2": JSON_VALUES})
MANIFESTS = st.fixed_dictionaries(
    {}, optional={"node": st.sampled_from(["navigation", "lamp", ""]) | SCALARS, "description": SCALARS,
                  "$schema": SCALARS, "tools": st.lists(TOOLS, max_size=4) | JSON_VALUES,
                  "snapshots": st.lists(SNAPSHOTS, max_size=3) | JSON_VALUES, "extra": JSON_VALUES},
) | JSON_VALUES


def _documented(exc: ManifestError) -> None:
    assert exc.message and exc.fix and exc.path.startswith("$"), exc


@bounded(400)
@given(MANIFESTS)
@example({"node": "n", "tools": [{"name": "t", "rpc": "r", "description": "d",
                                  "parameters": {"type": "object", "properties": {"a": {"$ref": "#/x"}}}}]})
def test_manifest_values_give_a_manifest_or_manifest_errors(data: Any) -> None:
    try:
        validate_manifest(data, "fuzz.json")
    except ManifestError as exc:
        _documented(exc)


@bounded(300)
@given(st.one_of(st.text(max_size=200), MANIFESTS.map(json.dumps),
                 MANIFESTS.map(lambda m: json.dumps(m)[: len(json.dumps(m)) // 2]),
                 st.integers(1, 5000).map(lambda n: "[" * n + "]" * n)))
@example('{"node": "a", "node": "b"}')
@example("NaN")
@example('{"node": 1e999}')
def test_manifest_texts_give_a_manifest_or_manifest_errors(text: str) -> None:
    try:
        parse_manifest(text, "fuzz.json")
    except ManifestError as exc:
        _documented(exc)


@bounded(60)
@given(st.lists(st.tuples(st.sampled_from(["navigation", "lamp", "base"]), st.booleans(),
                          st.binary(max_size=60) | MANIFESTS.map(lambda m: json.dumps(m).encode())), max_size=4))
def test_a_folder_of_random_manifest_files_loads_what_it_can(files: list[tuple[str, bool, bytes]]) -> None:
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        for node, nested, content in files:
            path = root / node / "mcp.json" if nested else root / f"{node}.mcp.json"
            path.parent.mkdir(exist_ok=True)
            path.write_bytes(content)
        loaded = load_manifest_dir(root)  # never raises for a bad file
    for errors in loaded.failed.values():
        for error in errors:
            _documented(error)
    assert set(loaded.manifests).isdisjoint(loaded.failed)


# --- addresses and URIs ---------------------------------------------------------------------

URI_PIECES = st.sampled_from(["zenoh://", "sim://", "memory://", "http://", "https://", "stdio:", "ros2://", "sim",
                              "tcp/", "udp/", "localhost", "127.0.0.1", "[::1]", ":7447", ":0", ":99999", ":-1",
                              "/mcp", "?", "&", "=", "mode=client", "mode=peer", "listen=", "connect=",
                              "speed=", "nodes=", "token=", "%", "%zz", "#", "@", "user:pw@", " ", "\x00",
                              "é", "1e9", "nan", "inf", ",", ";", "domain=", "/"])
URIS = st.lists(URI_PIECES | st.text(max_size=6), max_size=10).map("".join)


@bounded(600)
@given(URIS)
@example("zenoh://[::1]:7447?mode=client&connect=tcp/[::1]:7447")
@example("sim://?speed=nan")
@example("http://[::1/mcp")
def test_robot_addresses_parse_or_say_why(text: str) -> None:
    try:
        parse_robot_address(text)
    except MissingDependencyError:
        pass
    except ConfigError as exc:
        assert str(exc)


@bounded(400)
@given(URIS.map(lambda s: "zenoh://" + s) | URIS)
@example("zenoh://:7447")
@example("zenoh://host:7447?listen=tcp/0.0.0.0:99999")
def test_zenoh_uris_parse_or_say_why(text: str) -> None:
    for check in (ZenohSettings.from_uri, check_middleware_uri):
        try:
            check(text)
        except ConfigError as exc:
            assert str(exc)


# --- config files ---------------------------------------------------------------------------

TOML_KEYS = st.sampled_from(["robot", "llm", "voice", "address", "manifests", "sim_speed", "backends", "url",
                             "model", "api_key_file", "timeout_s", "wake_phrase", "x"])


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(value).replace("inf", "inf")
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return '"?"'


TOML_SCALARS = st.booleans() | st.integers(-(2**63), 2**63 - 1) | st.floats(allow_nan=False) | st.text(max_size=20)
TOML_DOCS = st.lists(
    st.tuples(st.sampled_from(["", "[robot]", "[llm]", "[voice]", "[[llm.backends]]", "[robot.sim]", "[x]"]),
              st.lists(st.tuples(TOML_KEYS, TOML_SCALARS | st.lists(TOML_SCALARS, max_size=3)), max_size=4)),
    max_size=4,
).map(lambda sections: "\n".join(
    head + "\n" + "\n".join(f"{k} = {_toml_value(v)}" for k, v in pairs) for head, pairs in sections))


@bounded(300)
@given(TOML_DOCS | st.text(max_size=120))
@example("[robot]\naddress = 'zenoh://host:99999'\n")
@example("[llm]\nbackends = [1, 2]\n")
def test_config_files_load_or_name_the_field(text: str) -> None:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "robovoice.toml"
        path.write_text(text, encoding="utf-8")
        try:
            assert isinstance(load_config(path), Config)
        except ConfigError as exc:
            assert str(path) in str(exc)


# --- WAV headers ----------------------------------------------------------------------------


def _wav_bytes() -> bytes:
    out = io.BytesIO()
    with wave.open(out, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(16000)
        w.writeframes((np.arange(800, dtype=np.int16) * 37).tobytes())
    return out.getvalue()


GOOD_WAV = _wav_bytes()
HEADER_FIELDS = [(4, "<I"), (16, "<I"), (20, "<H"), (22, "<H"), (24, "<I"), (28, "<I"), (32, "<H"), (34, "<H"),
                 (40, "<I")]  # RIFF size, fmt size, format, channels, rate, byte rate, align, bits, data size


@st.composite
def mutated_wavs(draw: st.DrawFn) -> bytes:
    data = bytearray(GOOD_WAV)
    for _ in range(draw(st.integers(1, 4))):
        if draw(st.booleans()):
            offset, fmt = draw(st.sampled_from(HEADER_FIELDS))
            bits = 8 * struct.calcsize(fmt)
            value = draw(st.sampled_from([0, 1, 2, 3, 0xFFFF, 2 ** (bits - 1), 2**bits - 1])
                         | st.integers(0, 2**bits - 1))
            struct.pack_into(fmt, data, offset, value)
        else:
            index = draw(st.integers(0, 63))
            data[index] = draw(st.integers(0, 255))
    cut = draw(st.sampled_from([len(data), 44, 43, 36, 12, 4, 0]) | st.integers(0, len(data)))
    return bytes(data[:cut])


@bounded(250)
@given(mutated_wavs())
def test_mutated_wav_headers_read_or_raise_audio_error(content: bytes) -> None:
    from robovoice.audio.wav import read_wav

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "x.wav"
        path.write_bytes(content)
        try:
            chunk = read_wav(path)
        except AudioError as exc:
            assert str(path) in str(exc)
        else:
            assert chunk.samples.dtype == np.int16


# --- payloads from other Zenoh processes -------------------------------------------------------

PAYLOADS = st.one_of(
    st.binary(max_size=80),
    JSON_VALUES.map(lambda v: json.dumps(v).encode()),
    st.integers(100, 20_000).map(lambda n: b"[" * n + b"]" * n),
    st.integers(100, 20_000).map(lambda n: b'{"progress":' * n + b"1" + b"}" * n),
    st.fixed_dictionaries({}, optional={"progress": SCALARS, "total": SCALARS, "message": SCALARS,
                                        "data": JSON_VALUES, "error": SCALARS, "details": JSON_VALUES}
                          ).map(lambda v: json.dumps(v).encode()),
)


@bounded(300)
@given(PAYLOADS)
def test_zenoh_payloads_decode_or_raise_value_error(data: bytes) -> None:
    from robovoice.middleware import zenoh_codec

    assert isinstance(zenoh_codec.decode_object(data), dict)  # never raises
    failure = zenoh_codec.failure_from_bytes(data, "node/rpc")  # never raises
    assert failure.code
    for strict in (zenoh_codec.decode, zenoh_codec.feedback_from_bytes):
        with contextlib.suppress(ValueError):  # also UnicodeDecodeError; nothing else
            strict(data)
