"""Checks shared by every URI and option parser: hosts, ports, numbers, query options, HTTP URLs.

Each check raises `ConfigError` naming the value, where it came from (`what`: a field, an
option, a URI) and the fix; none of them ever lets a value through unchanged when it cannot
mean what the user meant (an empty host, a port out of range, an unknown query option, a
negative speed ...). The core imports this module with no extras.
"""

from __future__ import annotations

import math
import re
from collections.abc import Collection, Mapping
from urllib.parse import SplitResult, parse_qs, urlsplit

from robovoice.errors import ConfigError

_HOSTNAME = re.compile(r"^(?=.{1,253}$)[A-Za-z0-9_](?:[A-Za-z0-9_.-]*[A-Za-z0-9_])?$")
_IPV6 = re.compile(r"^\[[0-9A-Fa-f:.]+(?:%[A-Za-z0-9_.-]+)?\]$")
SECRET_NAMES = ("token", "key", "secret", "password", "auth")


def split_uri(text: str, what: str = "URI") -> SplitResult:
    """`urlsplit`, with its ``ValueError`` (an unclosed ``[`` of an IPv6 host) as a `ConfigError`."""
    try:
        return urlsplit(text)
    except ValueError as exc:
        raise ConfigError(f"{what} {text!r} is not a valid URI: {exc}") from None


def check_host(host: str, what: str, example: str) -> str:
    """A host name, an IPv4 address or a bracketed IPv6 address (``[::1]``)."""
    if not host:
        raise ConfigError(f"{what}: the host is empty; write e.g. {example}")
    if ":" in host and not host.startswith("["):
        raise ConfigError(f"{what}: write an IPv6 address in brackets, e.g. [{host}], not {host!r}")
    if not (_HOSTNAME.match(host) or _IPV6.match(host)):
        raise ConfigError(f"{what}: {host!r} is not a host name or address; write e.g. {example}")
    return host


def check_port(text: str, what: str, *, allow_zero: bool = False) -> int:
    """A TCP/UDP port number, 1 to 65535 (0 too where `allow_zero`: the OS picks one)."""
    low = 0 if allow_zero else 1
    if not text.isdigit() or not low <= int(text) <= 65535:
        raise ConfigError(f"{what}: port must be a number from {low} to 65535, not {text!r}")
    return int(text)


def split_host_port(netloc: str, what: str, example: str) -> tuple[str, int | None]:
    """``HOST[:PORT]`` (``[v6]:PORT`` for IPv6) → (host, port or None); no user names or passwords."""
    if "@" in netloc:
        raise ConfigError(f"{what}: no user name or password in the address ({netloc!r}); write e.g. {example}")
    if netloc.startswith("["):
        close = netloc.find("]")
        if close < 0:
            raise ConfigError(f"{what}: unclosed '[' in {netloc!r}; write e.g. {example}")
        host, rest = netloc[: close + 1], netloc[close + 1:]
        if rest and not rest.startswith(":"):
            raise ConfigError(f"{what}: unexpected {rest!r} after {host}; write e.g. {example}")
        port_text = rest[1:] if rest else None
    elif netloc.count(":") > 1:
        raise ConfigError(f"{what}: write an IPv6 address in brackets, e.g. [::1]:7447, not {netloc!r}")
    else:
        host, sep, port_text_or_empty = netloc.partition(":")
        port_text = port_text_or_empty if sep else None
    check_host(host, what, example)
    return host, None if port_text is None else check_port(port_text, what)


def positive_number(text: str | float, what: str, *, maximum: float = math.inf) -> float:
    """A finite number > 0 (and ≤ `maximum`)."""
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise ConfigError(f"{what} must be a number, not {text!r}") from None
    if not (math.isfinite(value) and 0 < value <= maximum):
        bound = "" if math.isinf(maximum) else f" and at most {maximum:g}"
        raise ConfigError(f"{what} must be greater than 0{bound}, not {text!r}")
    return value


def query_options(parts: SplitResult, what: str, known: Collection[str], *,
                  repeatable: Collection[str] = ()) -> dict[str, list[str]]:
    """The query of a URI as ``{name: [values]}``: only `known` names, each once unless `repeatable`,
    and no name without ``=value``."""
    if not parts.query:
        return {}
    for item in parts.query.split("&"):
        if "=" not in item:
            raise ConfigError(f"{what}: query option {item!r} needs a value (name=value); "
                              f"known options: {', '.join(sorted(known))}")
    options = parse_qs(parts.query, keep_blank_values=True, strict_parsing=True)
    unknown = sorted(set(options) - set(known))
    if unknown:
        raise ConfigError(f"{what}: unknown option(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}")
    for name, values in options.items():
        if len(values) > 1 and name not in repeatable:
            raise ConfigError(f"{what}: option {name!r} given {len(values)} times")
    return options


def refuse_secrets(options: Mapping[str, object], what: str, fix: str) -> None:
    """Secrets never travel in a URI (logs, process lists and shell history keep them)."""
    for name in options:
        if any(word in name.lower() for word in SECRET_NAMES):
            raise ConfigError(f"{what}: no secrets in the URI (option {name!r}); {fix}")


def check_http_url(url: str, what: str, *, example: str, secret_fix: str) -> SplitResult:
    """An ``http://`` or ``https://`` URL with a valid host and port, no user name or password,
    and no secret in its query. Returns its parts."""
    parts = split_uri(url, what)
    if parts.scheme not in ("http", "https"):
        raise ConfigError(f"{what}: expected an http:// or https:// URL, e.g. {example}, not {url!r}")
    if not parts.netloc:
        raise ConfigError(f"{what}: {url!r} has no host; write e.g. {example}")
    if "@" in parts.netloc:
        raise ConfigError(f"{what}: no user name or password in the URL {url!r}; {secret_fix}")
    split_host_port(parts.netloc, f"{what} {url!r}", example)
    refuse_secrets(parse_qs(parts.query, keep_blank_values=True), f"{what} {url!r}", secret_fix)
    return parts
