"""Tool calls that a server returns as text in ``content`` instead of ``tool_calls``.

Servers without a tool-call parser for the model pass its raw call syntax through:

* Qwen2.5 / Hermes: ``<tool_call>\\n{"name": "x", "arguments": {...}}\\n</tool_call>`` (one or several,
  possibly after a sentence),
* llama-cpp-python's ``chatml-function-calling``: ``functions.x:\\n{...}`` heads, or a bare
  ``functions.x:`` (its plain-reply path is constrained by the follow-up grammar),
* Mistral: ``[TOOL_CALLS][{"name": "x", "arguments": {...}}]``,
* a bare ``{"name": "x", "arguments": {...}}`` object that starts the answer (what follows it, often
  a result the model invents, is dropped),
* the same object as the answer's start, wrapped in a tag of the prompt's or a Markdown code fence
  (Qwen2.5-Coder under its own GGUF template writes ``<tools>\n{"name": "x", "arguments": {}}\n</tools>``,
  the tag its prompt lists the tools in, or the call between two lines of three backticks, and
  often goes on to invent the result: that rest is dropped).

A call object of an offered tool without ``arguments`` (``{"name": "return_to_dock"}``) is a call
with none.

`TextCallParser` is fed the streamed content. It releases text as soon as it cannot be the start
of such a call and holds the rest; at the end it turns what it held into `TextCall`s, or releases
it as text when it was not a call after all ("I have many functions." is still spoken). A bare JSON
object counts only when its name is an offered tool (it could be a JSON answer); the other forms are
unambiguous, so an unknown name becomes a call the assistant answers with an unknown-tool error.
"""

from __future__ import annotations

import json
import logging
import re
from collections.abc import Collection, Iterator
from dataclasses import dataclass
from typing import Any

log = logging.getLogger(__name__)

TOOL_CALL_OPEN = "<tool_call>"
TOOL_CALL_CLOSE = "</tool_call>"
FUNCTIONS_PREFIX = "functions."
MISTRAL_CALLS = "[TOOL_CALLS]"

_ANYWHERE = (TOOL_CALL_OPEN, MISTRAL_CALLS)  # start a call wherever they appear
_LINE_START = (FUNCTIONS_PREFIX,)  # start a call at the start of a line
_FUNCTION_HEAD = re.compile(r"^[ \t]*functions\.([A-Za-z_][\w.\-]*)[ \t]*:", re.MULTILINE)
_BLOCK = re.compile(re.escape(TOOL_CALL_OPEN) + r"(.*?)(?:" + re.escape(TOOL_CALL_CLOSE) + r"|\Z)", re.DOTALL)
_NAME = re.compile(r'"name"\s*:\s*"([^"]+)"')
# `<tools>` or a Markdown code fence starting the answer: maybe a wrapped call
_OPENING_TAG = re.compile(r"<([a-z_]+)>|```(?:json)?")
_TAG_PREFIX = re.compile(r"(?:<[a-z_]*|`{1,3}(?:j(?:s(?:on?)?)?)?)\Z")  # what could still grow into one


@dataclass(frozen=True, slots=True)
class TextCall:
    """A call found in the text: the tool's name and its arguments as JSON text."""

    name: str
    arguments: str


class TextCallParser:
    """See the module docstring. `feed` each content delta, then `finish` once."""

    def __init__(self, tool_names: Collection[str]) -> None:
        self._names = frozenset(tool_names)
        self._held = ""
        self._released_any = False  # non-blank text released: a bare JSON object can no longer be the answer
        self._line_start = True  # the released text ends a line (or nothing was released)
        self._capturing = False  # a call began: everything from there is held to the end

    def feed(self, delta: str) -> str:
        """Take one content delta; the text that is safe to release now ('' if none)."""
        self._held += delta
        if self._capturing:
            return ""
        marker = self._first_marker(self._held)
        if marker is not None:
            self._capturing = True
            return self._release(marker)
        return self._release(self._partial_tail(self._held))

    def finish(self) -> tuple[str, list[TextCall]]:
        """The end of the content: the text still to release, and the calls found in it."""
        held, self._held = self._held, ""
        if not self._capturing:
            return held, []
        self._capturing = False
        text, calls = _parse_calls(held, self._names)
        if calls:
            log.debug("%d tool call(s) written as text in the content: %s", len(calls), [c.name for c in calls])
        return text, calls

    def _release(self, upto: int) -> str:
        out, self._held = self._held[:upto], self._held[upto:]
        if out.strip():
            self._released_any = True
        if out:
            self._line_start = out.endswith("\n")
        return out

    def _at_line_start(self, text: str, index: int) -> bool:
        before = text[:index]
        line = before.rsplit("\n", 1)
        if len(line) == 1:  # no newline held before it: depends on what was released
            return self._line_start and not before.strip(" \t")
        return not line[1].strip(" \t")

    def _first_marker(self, text: str) -> int | None:
        """Where the first complete call marker in `text` begins, if any."""
        found: list[int] = [i for m in _ANYWHERE if (i := text.find(m)) >= 0]
        for m in _LINE_START:
            start = 0
            while (i := text.find(m, start)) >= 0:
                if self._at_line_start(text, i):
                    found.append(i)
                    break
                start = i + 1
        if not self._released_any:
            stripped = text.lstrip()
            if stripped.startswith(("{", "[")) or _OPENING_TAG.match(stripped):
                found.append(len(text) - len(stripped))
        return min(found) if found else None

    def _partial_tail(self, text: str) -> int:
        """Where a tail of `text` that could still grow into a marker begins (len(text) if none)."""
        if not self._released_any and not text.strip():
            return 0  # leading blanks: wait for the first word
        if not self._released_any and _TAG_PREFIX.match(text.lstrip()):
            return 0  # "<too": maybe a wrapped call
        for i in range(max(0, len(text) - len(max(_ANYWHERE + _LINE_START, key=len))), len(text)):
            tail = text[i:]
            if any(m.startswith(tail) for m in _ANYWHERE):
                return i
            if any(m.startswith(tail) for m in _LINE_START) and self._at_line_start(text, i):
                return i
        return len(text)


def _parse_calls(text: str, names: frozenset[str]) -> tuple[str, list[TextCall]]:
    """Calls in `text` (which begins with a marker, or blanks then ``{``/``[``) and the text left over."""
    stripped = text.strip()
    if TOOL_CALL_OPEN in text:
        return _hermes(text)
    if stripped.startswith(MISTRAL_CALLS):
        calls = list(_json_calls(stripped[len(MISTRAL_CALLS) :], None))
        return ("", calls) if calls else (text, [])
    if stripped.startswith(FUNCTIONS_PREFIX):
        return _functions(text)
    if tag := _OPENING_TAG.match(stripped):  # ``<tools>{…}</tools>``: `_json_calls` stops at the JSON's end
        stripped = stripped[tag.end() :].lstrip()
    calls = list(_json_calls(stripped, names))  # a bare JSON answer: only a call of an offered tool
    return ("", calls) if calls else (text, [])


def _hermes(text: str) -> tuple[str, list[TextCall]]:
    calls: list[TextCall] = []
    for block in _BLOCK.finditer(text):
        body = block.group(1).strip()
        found = list(_json_calls(body, None))
        if found:
            calls.extend(found)
        elif name := _NAME.search(body):  # broken JSON: the model gets the parse error back
            calls.append(TextCall(name.group(1), body))
        else:
            log.warning("dropped a <tool_call> block with no function name: %r", body[:200])
    rest = _BLOCK.sub(" ", text).replace(TOOL_CALL_CLOSE, " ")
    return (" ".join(rest.split()) if rest.strip() else ""), calls


def _functions(text: str) -> tuple[str, list[TextCall]]:
    heads = list(_FUNCTION_HEAD.finditer(text))
    if not heads:
        return text, []  # "functions." at a line start, but no call head after it
    calls: list[TextCall] = []
    for head, nxt in zip(heads, [*heads[1:], None], strict=True):
        end = nxt.start() if nxt is not None else len(text)
        calls.append(TextCall(head.group(1), text[head.end() : end].strip()))
    return text[: heads[0].start()], calls


def _json_calls(text: str, names: frozenset[str] | None) -> Iterator[TextCall]:
    """Calls from a JSON object or list of objects with ``name`` and ``arguments`` (or ``parameters``)
    at the start of `text`; with `names`, only those of these tools. Text after the JSON is not
    read: the model going on to write a result it has not seen."""
    try:
        data, _ = json.JSONDecoder().raw_decode(text)
    except json.JSONDecodeError:
        data = _undoubled(text)
        if data is None:
            return
    for item in data if isinstance(data, list) else [data]:
        call = _call_from_object(item)
        if call is None or (names is not None and call.name not in names):
            return
    for item in data if isinstance(data, list) else [data]:
        call = _call_from_object(item)
        if call is not None:
            yield call


def _undoubled(text: str) -> Any | None:
    """Calls whose braces a chat template doubled (``{{"name": …}}}}``, one or several: Jinja's
    escaped ``{{`` rendered literally, seen from the Qwen GGUF's own template): the object inside
    (a list of them when there are several); None unless `text` starts with that."""
    rest = text.lstrip()
    found: list[Any] = []
    while rest:
        if not rest.startswith("{{"):
            if found:
                break  # what follows the calls
            return None
        inner = "{" + rest.lstrip("{")
        if not inner[1:].lstrip().startswith('"'):
            return None
        try:
            data, end = json.JSONDecoder().raw_decode(inner)
        except json.JSONDecodeError:
            if found:
                break
            return None
        found.append(data)
        rest = inner[end:].lstrip().lstrip("}").lstrip()
    if not found:
        return None
    return found if len(found) > 1 else found[0]


def _call_from_object(item: Any) -> TextCall | None:
    if not isinstance(item, dict) or not isinstance(item.get("name"), str):
        return None
    if "arguments" not in item and "parameters" not in item:
        return TextCall(item["name"], "{}") if len(item) == 1 else None  # {"name": "return_to_dock"}
    arguments = item.get("arguments", item.get("parameters"))
    if isinstance(arguments, str):
        return TextCall(item["name"], arguments)
    return TextCall(item["name"], json.dumps(arguments if arguments is not None else {}))
