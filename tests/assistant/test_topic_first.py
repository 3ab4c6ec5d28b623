"""The thing said before what to do with it, as English shaped by a sign language puts it
(assistant/topic_first.py): plain code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.topic_first import from_topic_first


@pytest.mark.parametrize(("said", "english"), [
    ("lamp, switch off now", "switch off the lamp now"),
    ("Clara call, finish.", "end the call."),
    ("Then garage... no. Charge, you go.", "Then garage... no. go and charge."),
    ("Telly, on.", "Telly on."),
    ("Then bedroom, you go please", "Then go to the bedroom please"),
    # not these shapes: left as said
    ("The lamp, is it on?", "The lamp, is it on?"),
    ("Ben's call ended early.", "Ben's call ended early."),
    ("Ben, you go first.", "Ben, you go first."),
])
def test_the_thing_first_is_put_in_english_order(said: str, english: str) -> None:
    assert from_topic_first(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("projector, switch on please", ("switch on the projector please",)),
    ("Clara call, end. Telly, off. Then charger, you go.", ("end the call", "Telly off", "go to the charger")),
    ("Finish call. After that, you charge go.", ("Finish call", "go charge")),
])
def test_they_are_read_as_the_steps_they_ask(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


@pytest.mark.parametrize(("said", "steps"), [
    # text test v125: the doctor's title said in lower case; a terse command after "before that"
    ("End this call now, then doctor Weber call, after that projector on.",
     ("End this call now", "call doctor Weber", "projector on")),
    ("Ring Anna, but before that projector on.", ("projector on", "Ring Anna")),
    ("Ring Anna, but before that projector on, please.", ("projector on", "Ring Anna")),  # no "before that" step
    ("call Ben, but before, go to kitchen, please.", ("go to kitchen", "call Ben")),  # a bare "before" (audio v116)
])
def test_a_lower_case_title_and_a_terse_command_put_first(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
