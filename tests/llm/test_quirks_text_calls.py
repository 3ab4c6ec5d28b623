"""`TextCallParser` (tool calls written as text, however the stream splits them) and
`retry_after_seconds` (the Retry-After header's two forms)."""

from __future__ import annotations

from email.utils import formatdate

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from robovoice.llm.retry_after import retry_after_seconds
from robovoice.llm.text_calls import TextCall, TextCallParser

NAMES = ("navigate_to", "get_battery_state", "set_projector_power")
DRIVE = TextCall("navigate_to", '{"target": "kitchen"}')
BATTERY = TextCall("get_battery_state", "{}")

CASES: list[tuple[str, str, list[TextCall]]] = [
    ('<tool_call>\n{"name": "navigate_to", "arguments": {"target": "kitchen"}}\n</tool_call>', "", [DRIVE]),
    ('Sure.\n<tool_call>\n{"name": "navigate_to", "arguments": {"target": "kitchen"}}\n</tool_call>\n'
     '<tool_call>\n{"name": "get_battery_state", "arguments": {}}\n</tool_call>', "Sure.\n", [DRIVE, BATTERY]),
    ("functions.get_battery_state:", "", [TextCall("get_battery_state", "")]),
    ('functions.navigate_to:\n{"target": "kitchen"}\nfunctions.get_battery_state:\n{}', "", [DRIVE, BATTERY]),
    ('  {"name": "navigate_to", "arguments": {"target": "kitchen"}}', "", [DRIVE]),
    ('{"name": "navigate_to", "parameters": {"target": "kitchen"}}', "", [DRIVE]),  # Llama 3 style
    ('{"name": "navigate_to", "arguments": "{\\"target\\": \\"kitchen\\"}"}', "", [DRIVE]),  # arguments as a string
    ('[TOOL_CALLS][{"name": "navigate_to", "arguments": {"target": "kitchen"}}]', "", [DRIVE]),
    ('Going now.\nfunctions.navigate_to:\n{"target": "kitchen"}', "Going now.\n", [DRIVE]),
    # the Qwen GGUF's own template through llama-cpp-python's server: Jinja's escaped braces, rendered literally
    ('{{"name": "navigate_to", "arguments": {"target": "kitchen"}}}}', "", [DRIVE]),
    ('{{"name": "get_battery_state", "arguments": {}}}}\n'
     '{{"name": "navigate_to", "arguments": {"target": "kitchen"}}}}', "", [BATTERY, DRIVE]),
    # the same template through llama-server and llama-cpp-python, after a look-up hint: the call in the
    # tag the prompt lists the tools in, then an invented result (dropped), or cut off by max_tokens
    ('<tools>\n{"name": "get_battery_state", "arguments": {}}\n</tools>\nThe battery now: 75%.', "", [BATTERY]),
    ('<tools>\n{"name": "get_battery_state", "arguments": {}}\n</to', "", [BATTERY]),
    ('```\n{{"name": "get_battery_state", "arguments": {}}}}\n```\nThe battery now: 75%.', "", [BATTERY]),
    ('```json\n{"name": "navigate_to", "arguments": {"target": "kitchen"}}\n```', "", [DRIVE]),
    ('{{"name": "get_battery_state"}}', "", [BATTERY]),  # no arguments at all
    # the call, then a result the model made up, fenced: the rest is dropped
    ('{{"name": "get_battery_state", "arguments": {}}}}\n```\nThe battery now: 75%.\n```', "", [BATTERY]),
    ('{"name": "navigate_to", "arguments": {"target": "kitchen"}}\nI have arrived.', "", [DRIVE]),
]

PLAIN = [
    "The kitchen is to the left.",
    "I have several functions. functions are useful.",
    "functions. That is a plural noun.",
    "for sure, 3 < 4 and <b>bold</b> and a {brace}.",
    '{"answer": 42}',  # a JSON answer that is not a call
    '{"name": "dance", "arguments": {}}',  # a call of a tool that was not offered: text (the guard drops it)
    "[laughs] Good one.",
    "{{not a call}}",
    '{{"name": "dance", "arguments": {}}}}',  # doubled braces, but not an offered tool
    '<tools>\n{"type": "function", "function": {"name": "get_battery_state"}}\n</tools>',  # a tool read back
    '<tools>{"name": "dance", "arguments": {}}</tools>',  # wrapped, but not an offered tool
    "<b>Bold</b> words.",
    "```\nprint('hello')\n```",  # a code block that is not a call
    '{"name": "Ben"}',  # a name, but not of an offered tool
]


def split_feed(text: str, cuts: list[int]) -> tuple[list[str], str, list[TextCall]]:
    parser = TextCallParser(NAMES)
    released: list[str] = []
    start = 0
    for cut in [*sorted(c for c in cuts if 0 < c < len(text)), len(text)]:
        released.append(parser.feed(text[start:cut]))
        start = cut
    rest, calls = parser.finish()
    return released, rest, calls


@pytest.mark.parametrize(("text", "spoken", "calls"), CASES)
@pytest.mark.parametrize("size", [1, 2, 5, 1000])
def test_calls_are_found_whatever_the_chunking(text: str, spoken: str, calls: list[TextCall], size: int) -> None:
    released, rest, found = split_feed(text, list(range(size, len(text), size)))
    assert found == calls
    assert ("".join(released) + rest).strip() == spoken.strip()


@settings(max_examples=60, deadline=None)
@given(case=st.sampled_from(CASES), cuts=st.lists(st.integers(0, 120), max_size=12))
def test_no_piece_of_a_call_is_ever_released(case: tuple[str, str, list[TextCall]], cuts: list[int]) -> None:
    text, spoken, calls = case
    released, rest, found = split_feed(text, cuts)
    assert found == calls
    said = "".join(released) + rest
    assert said.strip() == spoken.strip()
    assert "<tool" not in said and "functions.n" not in said and "functions.g" not in said and '"name"' not in said


@settings(max_examples=60, deadline=None)
@given(text=st.sampled_from(PLAIN), cuts=st.lists(st.integers(0, 60), max_size=10))
def test_plain_text_comes_out_whole_and_unchanged(text: str, cuts: list[int]) -> None:
    released, rest, found = split_feed(text, cuts)
    assert found == [] and "".join(released) + rest == text


def test_plain_text_is_released_as_it_comes() -> None:
    parser = TextCallParser(NAMES)
    assert parser.feed("Hello, ") == "Hello, "
    assert parser.feed("I am <tool") == "I am "  # could be a <tool_call>: held
    assert parser.feed("s> here.") == "<tools> here."
    assert parser.feed("\nfunc") == "\n"  # could be functions.x: at a line start: held
    assert parser.feed("tional.") == "functional."
    assert parser.finish() == ("", [])


def test_an_unclosed_tool_call_tag_is_still_a_call_and_a_nameless_one_is_dropped() -> None:
    parser = TextCallParser(NAMES)
    parser.feed('<tool_call>{"name": "navigate_to", "arguments": {"target": "kitchen"}}')
    assert parser.finish() == ("", [DRIVE])
    parser = TextCallParser(NAMES)
    assert parser.feed("<tool_call>{}</tool_call> Done.") == ""
    assert parser.finish() == ("Done.", [])


@pytest.mark.parametrize(("value", "seconds"), [("3", 3.0), (" 0.5 ", 0.5), ("0", 0.0), ("-2", 0.0),
                                                ("", None), (None, None), ("soon", None), ("nan", None)])
def test_retry_after_seconds(value: str | None, seconds: float | None) -> None:
    assert retry_after_seconds(value) == seconds


def test_retry_after_as_an_http_date() -> None:
    now = 1_800_000_000.0
    assert retry_after_seconds(formatdate(now + 12, usegmt=True), now=now) == pytest.approx(12.0)
    assert retry_after_seconds(formatdate(now - 12, usegmt=True), now=now) == 0.0
    assert retry_after_seconds("Wed, 21 Oct 2015 07:28:00 -0000", now=now) == 0.0  # zone-less: GMT, long past


def test_the_embedded_model_writing_a_call_after_its_message_makes_a_call_not_words() -> None:
    """Seen on the embedded model (test v3, a compound request): after ``message:`` it wrote a
    sentence, then ``functions.navigate_to:`` and the arguments. The call is a call; only the
    sentence is words. The model's tokens are scripted here; the streaming code is the backend's."""
    import threading
    from typing import Any

    from robovoice.llm.base import TextDelta, ToolCallRequested, ToolSpec
    from robovoice.llm.local import LocalLlamaBackend
    from robovoice.llm.local_turn import Turn

    pieces = ["I'll go", " now.\n\nfunc", "tions.navigate_to:\n", '{ "target": ', '"hallway" }']

    class Scripted(LocalLlamaBackend):
        def _complete(self, turn: Turn, prompt: str, *, stream: bool, **kwargs: Any) -> Any:
            return iter([{"choices": [{"text": p, "finish_reason": None}]} for p in pieces]
                        + [{"choices": [{"text": "", "finish_reason": "stop"}]}])

    drive = ToolSpec("navigate_to", "Drive to a place.",
                     {"type": "object", "properties": {"target": {"type": "string"}}})
    events = list(Scripted()._stream_text(Turn(threading.Event()), "prompt", [drive]))
    assert "".join(e.text for e in events if isinstance(e, TextDelta)).strip() == "I'll go now."
    assert [(c.name, dict(c.arguments)) for c in events if isinstance(c, ToolCallRequested)] == [
        ("navigate_to", {"target": "hallway"})]
    assert events[-1].reason == "tool_calls"  # type: ignore[union-attr]
