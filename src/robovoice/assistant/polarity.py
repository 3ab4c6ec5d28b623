"""Which way a switch goes: a yes/no argument against the words of the request for it.

The embedded model can get a switch the wrong way round (text test v63: "douse the projector"
switched it on), and nothing else checks which way a switch goes. A tool
whose yes/no argument the manifest describes with a pair of opposite words ("true to switch
the projector on, false to switch it off") is checked against the request clauses that name
the tool or point back at it ("turn it off"): when they say exactly one of the two words and
the call sends the other value, it is sent the way they say (`righted`, through `gate.checked`).
Words that say neither ("douse", "kill", "fire up") are left to the model, as before: a check
that guesses would refuse right calls.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from typing import Any

from robovoice.assistant.fit import names, refers_back
from robovoice.assistant.lexicon import fragment, words
from robovoice.assistant.reading import ClauseKind, Intent

# Opposite words a yes/no argument's description may pair: the first for true, the second for false.
_OPPOSITES = (("on", "off"), ("open", "close"), ("up", "down"), ("start", "stop"), ("lock", "unlock"))
_VALUE_PHRASE = re.compile(r"\b(true|false) to ([^,;.]+)", re.IGNORECASE)


def _pair(description: str) -> tuple[str, str] | None:
    """The words the description says true and false mean ("on", "off"), or None."""
    phrases = {m.group(1).lower(): set(words(m.group(2))) for m in _VALUE_PHRASE.finditer(description)}
    if "true" not in phrases or "false" not in phrases:
        return None
    for yes, no in _OPPOSITES:
        for first, second in ((yes, no), (no, yes)):
            if first in phrases["true"] and second in phrases["false"] and second not in phrases["true"]:
                return first, second
    return None


def _names_it(text: str, name: str, declared: Sequence[str]) -> bool:
    """A verbless clause naming the tool's thing, which says what the request before it meant: "Put
    the thingy on. The picture box." (text test v97: the projector let through either way round)."""
    return bool(text) and fragment(text) and names(text, name, {}, declared)


def _wanted(intent: Intent, name: str, parameters: Mapping[str, Any], arguments: Mapping[str, Any],
            declared: Sequence[str]) -> tuple[str, str, bool] | None:
    """The yes/no argument this call sends the other way round from the words, the word they say
    ("off") and the value it means (False); None when the call goes the way they say, or they do
    not say."""
    properties = parameters.get("properties") or {}
    requests = [c.text if c.kind is ClauseKind.REQUEST else "" for c in intent.clauses]
    asked = [text for i, text in enumerate(requests) if text and (names(text, name, {}, declared) or refers_back(
        text) or (i + 1 < len(requests) and _names_it(requests[i + 1], name, declared)))]
    said = {w for text in asked for w in words(text)}
    for arg, value in arguments.items():
        schema = properties.get(arg)
        if not isinstance(value, bool) or not isinstance(schema, Mapping) or schema.get("type") != "boolean":
            continue
        pair = _pair(str(schema.get("description", "")))
        if pair is None or (pair[0] in said) == (pair[1] in said):
            continue  # neither word, or both ("off and on again"): nothing to go by
        wanted = pair[0] if pair[0] in said else pair[1]
        if (wanted == pair[0]) != value:
            return arg, wanted, not value
    return None


def wrong_way(intent: Intent, name: str, parameters: Mapping[str, Any], arguments: Mapping[str, Any],
              declared: Sequence[str]) -> str | None:
    """The word the request says ("off") when this call sends the opposite value, else None."""
    found = _wanted(intent, name, parameters, arguments, declared)
    return found[1] if found is not None else None


def righted(intent: Intent, name: str, parameters: Mapping[str, Any], arguments: Mapping[str, Any],
            declared: Sequence[str]) -> dict[str, Any] | None:
    """This call's arguments with its switch the way the words say ("switch the projector off"
    sent as on: true, as on: false), or None when it goes their way or they do not say."""
    found = _wanted(intent, name, parameters, arguments, declared)
    return None if found is None else {**arguments, found[0]: found[2]}
