"""ROS 2 message types as robovoice sees them: import by name, JSON Schema, JSON ⇄ message.

Everything comes from the metadata the generated Python classes carry (`SLOT_TYPES`,
`get_fields_and_field_types()`), so any installed interface package works without
rosidl_runtime_py. Conventions:

- `builtin_interfaces/Time` and `Duration` are numbers of seconds;
- integers carry their range (``int8`` … ``uint64``), fixed arrays their size, bounded
  sequences and strings their maximum length;
- byte arrays (``uint8[]``, ``octet[]``) come back as base64 strings;
- `sensor_msgs/CompressedImage` and (rgb8/bgr8/mono8/rgba8/bgra8) `sensor_msgs/Image` come back
  as ``{"mime_type": "image/...", "data": <base64>, ...}``, the wire form of an image.

`to_message` converts and range-checks every value *before* anything is sent: rclpy does not
(an int in a float field arrives as 0.0, 300 in a uint8 as 44). Errors are `ValueError`s
naming the field path.
"""

from __future__ import annotations

import base64
import importlib
import math
import re
import struct
import warnings
import zlib
from collections.abc import Mapping
from typing import Any

from robovoice.errors import MissingDependencyError

try:
    with warnings.catch_warnings():  # lark, under rosidl_generator_py, imports the deprecated sre_parse
        warnings.simplefilter("ignore", DeprecationWarning)
        import rosidl_generator_py  # noqa: F401  # imported by rclpy on the first message type: do it here
        from rosidl_parser import definition as d
except ImportError as exc:  # pragma: no cover - depends on the install
    raise MissingDependencyError("the ROS 2 middleware", "pip install 'robovoice[ros2]'") from exc

_TYPE_NAME = re.compile(r"^([A-Za-z][A-Za-z0-9_]*)/(msg|srv|action)/([A-Z][A-Za-z0-9]*)$")

INT_RANGES: dict[str, tuple[int, int]] = {
    "int8": (-(2**7), 2**7 - 1), "uint8": (0, 2**8 - 1), "char": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1), "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1), "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1), "uint64": (0, 2**64 - 1),
    "short": (-(2**15), 2**15 - 1), "unsigned short": (0, 2**16 - 1),
    "long": (-(2**31), 2**31 - 1), "unsigned long": (0, 2**32 - 1),
    "long long": (-(2**63), 2**63 - 1), "unsigned long long": (0, 2**64 - 1),
}
FLOAT32_MAX = 3.4028234663852886e38
_FLOATS = {"float", "double", "long double", "float32", "float64"}
_BYTES = {"octet", "byte"}
_TIME_TYPES = {("builtin_interfaces", "Time"), ("builtin_interfaces", "Duration")}


class TypeNotFoundError(LookupError):
    """A ROS 2 type name that does not import; `reason` says why, `fix` what to do."""

    def __init__(self, name: str, reason: str, fix: str) -> None:
        super().__init__(f"{name}: {reason}")
        self.reason = reason
        self.fix = fix


def parse_type_name(name: str) -> tuple[str, str, str]:
    """``"std_srvs/srv/SetBool"`` → ``("std_srvs", "srv", "SetBool")``."""
    match = _TYPE_NAME.match(name)
    if match is None:
        raise TypeNotFoundError(
            name, "not a ROS 2 type name",
            "write PACKAGE/msg/Type, PACKAGE/srv/Type or PACKAGE/action/Type, e.g. std_srvs/srv/SetBool",
        )
    package, kind, type_name = match.groups()
    return package, kind, type_name


def import_type(name: str) -> Any:
    """The generated class of a message, service or action type, by its full name."""
    package, kind, type_name = parse_type_name(name)
    try:
        module = importlib.import_module(f"{package}.{kind}")
    except ImportError:
        wheel = "ros-kilted-" + package.replace("_", "-")
        raise TypeNotFoundError(
            name, f"the interface package {package!r} is not installed",
            f"install it (pip install {wheel}, or build and install the package), or correct the name",
        ) from None
    found = getattr(module, type_name, None)
    if found is None:
        known = sorted(n for n in dir(module) if n[:1].isupper() and "_" not in n)
        raise TypeNotFoundError(
            name, f"{package}/{kind} has no type {type_name!r}",
            f"use one of: {', '.join(known[:20]) or 'none'}",
        )
    return found


def _is_time(t: d.NamespacedType) -> bool:
    return (next(iter(t.namespaces)), t.name) in _TIME_TYPES


def _nested_class(t: d.NamespacedType) -> Any:
    module = importlib.import_module(".".join(t.namespaces))
    return getattr(module, t.name)


def fields_of(msg_class: Any) -> dict[str, Any]:
    """Field name → rosidl type object, in declaration order."""
    names = list(msg_class.get_fields_and_field_types())
    return dict(zip(names, msg_class.SLOT_TYPES, strict=True))


def field_type(msg_class: Any, path: str) -> Any:
    """The rosidl type of a dotted field path (``pose.pose.position.x``); KeyError names the
    first part the type lacks."""
    current: Any = d.NamespacedType(msg_class.__module__.split(".")[:2], msg_class.__name__)
    cls = msg_class
    for part in path.split("."):
        if not isinstance(current, d.NamespacedType):
            raise KeyError(part)
        fields = fields_of(cls)
        if part not in fields:
            raise KeyError(part)
        current = fields[part]
        if isinstance(current, d.NamespacedType):
            cls = _nested_class(current)
    return current


def field_names(msg_class: Any) -> list[str]:
    return list(msg_class.get_fields_and_field_types())


# --- JSON Schema ---------------------------------------------------------------------------


def type_schema(t: Any) -> dict[str, Any]:
    """The JSON Schema of one rosidl type."""
    if isinstance(t, d.BasicType):
        return _basic_schema(t.typename)
    if isinstance(t, d.AbstractString):
        schema: dict[str, Any] = {"type": "string"}
        if isinstance(t, d.BoundedString | d.BoundedWString):
            schema["maxLength"] = t.maximum_size
        return schema
    if isinstance(t, d.NamespacedType):
        if _is_time(t):
            return {"type": "number", "description": "seconds"}
        return message_schema(_nested_class(t))
    if isinstance(t, d.AbstractNestedType):
        array: dict[str, Any] = {"type": "array", "items": type_schema(t.value_type)}
        if isinstance(t, d.Array):
            array["minItems"] = array["maxItems"] = t.size
        elif isinstance(t, d.BoundedSequence):
            array["maxItems"] = t.maximum_size
        return array
    raise TypeError(f"unsupported ROS 2 field type {t!r}")


def _basic_schema(name: str) -> dict[str, Any]:
    if name == "boolean":
        return {"type": "boolean"}
    if name in _FLOATS:
        return {"type": "number"}
    if name in _BYTES:
        return {"type": "integer", "minimum": 0, "maximum": 255}
    low, high = INT_RANGES[name]
    return {"type": "integer", "minimum": low, "maximum": high}


def message_schema(msg_class: Any) -> dict[str, Any]:
    """An object schema with one property per field (none required: ROS fills defaults)."""
    props = {name: type_schema(t) for name, t in fields_of(msg_class).items()}
    return {"type": "object", "properties": props, "additionalProperties": False}


# --- JSON → message --------------------------------------------------------------------------


def to_message(msg_class: Any, value: Mapping[str, Any], path: str = "") -> Any:
    """Build a message from a JSON object, converting and range-checking every field."""
    if not isinstance(value, Mapping):
        raise ValueError(f"{path or 'the message'}: expected an object, got {type(value).__name__}")
    fields = fields_of(msg_class)
    kwargs: dict[str, Any] = {}
    for key, item in value.items():
        where = f"{path}.{key}" if path else key
        if key not in fields:
            raise ValueError(f"{where}: {msg_class.__name__} has no field {key!r} (it has {', '.join(fields)})")
        kwargs[key] = convert(fields[key], item, where)
    return msg_class(**kwargs)


def convert(t: Any, value: Any, path: str) -> Any:
    """One JSON value as the Python value rclpy expects for the rosidl type `t`."""
    if isinstance(t, d.BasicType):
        return _basic(t.typename, value, path)
    if isinstance(t, d.AbstractString):
        if not isinstance(value, str):
            raise ValueError(f"{path}: expected a string, got {_kind(value)}")
        if isinstance(t, d.BoundedString | d.BoundedWString) and len(value) > int(t.maximum_size):
            raise ValueError(f"{path}: at most {t.maximum_size} characters")
        return value
    if isinstance(t, d.NamespacedType):
        cls = _nested_class(t)
        if _is_time(t) and not isinstance(value, Mapping):
            return _seconds(cls, value, path)
        return to_message(cls, value, path)
    if isinstance(t, d.AbstractNestedType):
        if isinstance(value, str) and isinstance(t.value_type, d.BasicType) and t.value_type.typename in (
            "uint8", "octet", "byte"
        ):
            value = list(base64.b64decode(value, validate=True))
        if not isinstance(value, list | tuple):
            raise ValueError(f"{path}: expected an array, got {_kind(value)}")
        if isinstance(t, d.Array) and len(value) != t.size:
            raise ValueError(f"{path}: expected exactly {t.size} items, got {len(value)}")
        if isinstance(t, d.BoundedSequence) and len(value) > t.maximum_size:
            raise ValueError(f"{path}: at most {t.maximum_size} items, got {len(value)}")
        return [convert(t.value_type, v, f"{path}[{i}]") for i, v in enumerate(value)]
    raise ValueError(f"{path}: unsupported field type {t!r}")


def _basic(name: str, value: Any, path: str) -> Any:
    if name == "boolean":
        if not isinstance(value, bool):
            raise ValueError(f"{path}: expected true or false, got {_kind(value)}")
        return value
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"{path}: expected a number, got {_kind(value)}")
    if name in _FLOATS:
        number = float(value)
        if not math.isfinite(number):
            raise ValueError(f"{path}: must be a finite number")
        if name in ("float", "float32") and abs(number) > FLOAT32_MAX:
            raise ValueError(f"{path}: {value} is out of range for a 32-bit float")
        return number
    if isinstance(value, float):
        if not value.is_integer():
            raise ValueError(f"{path}: expected an integer, got {value}")
        value = int(value)
    low, high = (0, 255) if name in _BYTES else INT_RANGES[name]
    if not low <= value <= high:
        raise ValueError(f"{path}: {value} is out of range for {name} ({low}..{high})")
    return bytes([value]) if name in _BYTES else value


def _seconds(cls: Any, value: Any, path: str) -> Any:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ValueError(f"{path}: expected a number of seconds, got {_kind(value)}")
    sec = math.floor(value)
    if not INT_RANGES["int32"][0] <= sec <= INT_RANGES["int32"][1]:
        raise ValueError(f"{path}: {value} s is out of range")
    return cls(sec=int(sec), nanosec=min(round((value - sec) * 1e9), 999_999_999))


def _kind(value: Any) -> str:
    if value is None:
        return "null"
    return {bool: "a boolean", int: "an integer", float: "a number", str: "a string",
            list: "an array", dict: "an object"}.get(type(value), type(value).__name__)


# --- message → JSON ----------------------------------------------------------------------------


def to_json(msg: Any) -> Any:
    """A message (or field value) as JSON: objects, numbers (times in seconds), base64 bytes."""
    cls = type(msg)
    if hasattr(cls, "get_fields_and_field_types"):
        ns = cls.__module__.split(".")[0]
        if (ns, cls.__name__) in _TIME_TYPES:
            return msg.sec + msg.nanosec / 1e9
        image = image_json(msg)
        if image is not None:
            return image
        return {name: field_json(t, getattr(msg, name)) for name, t in fields_of(cls).items()}
    if isinstance(msg, bytes | bytearray):
        return msg[0] if len(msg) == 1 else base64.b64encode(msg).decode("ascii")
    if isinstance(msg, float):
        return msg if math.isfinite(msg) else None
    if isinstance(msg, bool | int | str) or msg is None:
        return msg
    typecode = getattr(msg, "typecode", None)
    if typecode == "B":  # array.array of uint8: bytes
        return base64.b64encode(bytes(msg)).decode("ascii")
    if hasattr(msg, "tolist"):  # numpy arrays
        return [to_json(v) for v in msg.tolist()]
    if isinstance(msg, list | tuple) or hasattr(msg, "__iter__"):
        return [to_json(v) for v in msg]
    return str(msg)


def field_json(t: Any, value: Any) -> Any:
    """`to_json`, with 32-bit floats shown with the digits they hold (24.1, not 24.100000381469727)."""
    inner = t.value_type if isinstance(t, d.AbstractNestedType) else t
    if isinstance(inner, d.BasicType) and inner.typename in ("float", "float32"):
        converted = to_json(value)
        if isinstance(converted, list):
            return [_float32(v) for v in converted]
        return _float32(converted)
    return to_json(value)


def _float32(value: Any) -> Any:
    return float(f"{value:.7g}") if isinstance(value, float) else value


def stamp_of(msg: Any) -> float | None:
    """The message's ``header.stamp`` in UNIX seconds, when it has a non-zero one."""
    header = getattr(msg, "header", None)
    stamp = getattr(header, "stamp", None)
    if stamp is None or not hasattr(stamp, "sec"):
        return None
    seconds = float(stamp.sec + stamp.nanosec / 1e9)
    return seconds if seconds > 0 else None


_CHANNELS = {"rgb8": 3, "bgr8": 3, "rgba8": 4, "bgra8": 4, "mono8": 1}


def image_json(msg: Any) -> dict[str, Any] | None:
    """`sensor_msgs/CompressedImage` or `Image` as the image wire form; None for other types."""
    cls = type(msg)
    if not cls.__module__.startswith("sensor_msgs."):
        return None
    if cls.__name__ == "CompressedImage":
        fmt = str(msg.format).lower()
        mime = "image/png" if "png" in fmt else "image/jpeg"
        return {"mime_type": mime, "data": base64.b64encode(bytes(msg.data)).decode("ascii"), "format": msg.format}
    if cls.__name__ == "Image" and msg.encoding in _CHANNELS:
        png = encode_png(bytes(msg.data), int(msg.width), int(msg.height), int(msg.step), str(msg.encoding))
        return {"mime_type": "image/png", "data": base64.b64encode(png).decode("ascii"),
                "width": int(msg.width), "height": int(msg.height), "encoding": msg.encoding}
    return None


def encode_png(data: bytes, width: int, height: int, step: int, encoding: str) -> bytes:
    """A minimal PNG (stdlib zlib) of 8-bit raw pixels; BGR(A) is swapped to RGB(A)."""
    channels = _CHANNELS[encoding]
    row_bytes = width * channels
    rows = []
    for y in range(height):
        row = data[y * step: y * step + row_bytes]
        if encoding.startswith("bgr"):
            swapped = bytearray(row)
            swapped[0::channels], swapped[2::channels] = row[2::channels], row[0::channels]
            row = bytes(swapped)
        rows.append(b"\x00" + row)
    color = {1: 0, 3: 2, 4: 6}[channels]

    def chunk(tag: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, color, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(b"".join(rows), 6))
            + chunk(b"IEND", b""))
