"""Manifest errors as a group, JSON paths, and "did you mean" suggestions.

Every problem found in a manifest is one `robovoice.errors.ManifestError` (file, JSON
path, message, fix). A file with problems raises `ManifestErrors`, which *is* a
`ManifestError` (its attributes are those of the first problem, so ``except
ManifestError`` still works) and carries all of them in `errors`.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable, Sequence

from robovoice.errors import ManifestError

Loc = Sequence[str | int]

_IDENT = re.compile(r"^[A-Za-z_$][A-Za-z0-9_$]*$")


class ManifestErrors(ManifestError):
    """All the problems of one manifest (or of one check), in document order."""

    def __init__(self, errors: Iterable[ManifestError]) -> None:
        self.errors: tuple[ManifestError, ...] = tuple(sort_errors(errors))
        if not self.errors:
            raise ValueError("ManifestErrors needs at least one error")
        first = self.errors[0]
        super().__init__(first.source, first.path, first.message, first.fix)
        # Exception.args/str: every error on its own line.
        self.args = ("\n".join(format_error(e) for e in self.errors),)

    def __str__(self) -> str:
        return str(self.args[0])


def format_error(error: ManifestError) -> str:
    """The one-line report form: ``file: $.path: message (fix: ...)``."""
    return f"{error.source}: {error.path}: {error.message} (fix: {error.fix})"


def flatten(errors: Iterable[ManifestError]) -> list[ManifestError]:
    """Expand `ManifestErrors` groups into their single errors."""
    out: list[ManifestError] = []
    for error in errors:
        if isinstance(error, ManifestErrors):
            out.extend(error.errors)
        else:
            out.append(error)
    return out


def json_path(loc: Loc) -> str:
    """``("tools", 2, "parameters")`` → ``$.tools[2].parameters``."""
    parts = ["$"]
    for item in loc:
        if isinstance(item, int):
            parts.append(f"[{item}]")
        elif _IDENT.match(item):
            parts.append(f".{item}")
        else:
            parts.append("[" + _quote(item) + "]")
    return "".join(parts)


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


_PATH_TOKEN = re.compile(r"\[(\d+)\]|\.([^.\[]+)|\[\"((?:[^\"\\]|\\.)*)\"\]")


def _path_key(path: str) -> tuple[tuple[int, int | str], ...]:
    """Sort key putting ``$.tools[2]`` before ``$.tools[10]`` and parents before children."""
    key: list[tuple[int, int | str]] = []
    for match in _PATH_TOKEN.finditer(path):
        index, name, quoted = match.groups()
        key.append((0, int(index)) if index is not None else (1, name if name is not None else quoted))
    return tuple(key)


def sort_errors(errors: Iterable[ManifestError]) -> list[ManifestError]:
    """Flatten and order by file, then JSON path (stable for equal paths)."""
    return sorted(flatten(errors), key=lambda e: (e.source, _path_key(e.path)))


def nearest(word: str, choices: Iterable[str]) -> str | None:
    """The closest known spelling of `word`, if any is close enough."""
    pool = list(choices)
    lowered = {c.lower(): c for c in pool}
    if word.lower() in lowered:
        return lowered[word.lower()]
    found = difflib.get_close_matches(word, pool, n=1, cutoff=0.6)
    return found[0] if found else None


def did_you_mean(word: str, choices: Iterable[str], *, what: str = "") -> str:
    """``did you mean 'defaults'? (known fields: a, b, c)`` or just the list."""
    pool = sorted(choices)
    known = ", ".join(repr(c) for c in pool) if pool else "none"
    listing = f"known {what}: {known}" if what else f"known: {known}"
    guess = nearest(word, pool)
    return f"did you mean {guess!r}? ({listing})" if guess is not None else listing


def describe_json(value: object) -> str:
    """A JSON value's type in words, for "expected X, got Y" messages."""
    match value:
        case None:
            return "null"
        case bool():
            return f"a boolean ({str(value).lower()})"
        case int() | float():
            return f"a number ({value})"
        case str():
            shown = value if len(value) <= 40 else value[:37] + "..."
            return f"a string ({shown!r})"
        case list() | tuple():
            return "an array"
        case dict():
            return "an object"
        case _:
            return type(value).__name__
