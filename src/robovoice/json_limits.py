"""How deep a JSON text nests, measured without parsing it (no recursion, linear time).

Used before ``json.loads`` wherever JSON arrives from outside (manifests, HTTP bodies): the
standard parser recurses once per level and raises ``RecursionError`` near 1000 levels, and
the validators after it recurse too.
"""

from __future__ import annotations

import re

# One left-to-right pass: a string (its closing quote optional, so an unterminated one takes the
# rest of the body at once instead of being rescanned from every quote inside it: no quadratic
# time on hostile input) or a bracket.
_TOKEN = re.compile(rb'"(?:[^"\\]+|\\.)*"?|[\[\]{}]', re.DOTALL)
_OPENERS = frozenset(b"[{")


def json_depth_exceeds(body: bytes, max_depth: int) -> bool:
    """Whether `body` (JSON text, possibly malformed) nests arrays/objects deeper than `max_depth`.

    Brackets inside strings do not count; a malformed body is measured as far as its
    brackets go (the parser refuses it later anyway). Linear time, whatever the input.
    """
    if body.count(b"[") + body.count(b"{") <= max_depth:
        return False
    depth = 0
    for match in _TOKEN.finditer(body):
        first = match[0][0]
        if first == 0x22:  # '"': a string, brackets inside do not count
            continue
        if first in _OPENERS:
            depth += 1
            if depth > max_depth:
                return True
        else:
            depth = max(0, depth - 1)
    return False
