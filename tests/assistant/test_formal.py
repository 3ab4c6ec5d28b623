"""Formal requests (assistant/formal.py) and a sentence said to a person by name (assistant/addressee.py):
plain code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.formal import as_asked
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "plain"), [
    ("I am requesting you to kindly call Ben.", "please call Ben."),
    ("You are requested to proceed to the hallway.", "please proceed to the hallway."),
    ("Before that you may proceed to the kitchen.", "Before that proceed to the kitchen."),
    ("The video call may kindly be disconnected now.", "end the call now."),
    ("The projector should be switched off.", "switch the projector off."),
    ("Let the projector remain on.", "leave it on."),
    ("Prior to that, go to the hallway.", "before that, go to the hallway."),
    # what could happen, not what to do
    ("The call may be disconnected if the signal is weak.", "The call may be disconnected if the signal is weak."),
    ("You may be right about that.", "You may be right about that."),
])
def test_formal_requests_are_said_plainly(said: str, plain: str) -> None:
    assert as_asked(said) == plain


@pytest.mark.parametrize(("said", "steps"), [
    ("The call may be disconnected, the projector also may be put off, and thereafter kindly return to your dock.",
     ("end the call", "switch the projector off", "kindly return to your dock")),
    ("Kindly put on the projector, but before that you may proceed to the bedroom.",
     ("proceed to the bedroom", "Kindly put on the projector")),
    ("Let the projector remain on. Do not switch it off.", ()),
    # said to the person named, by a "you must come" later in the sentence
    ("Anna, the garden here is lovely now, you must come and see.", ()),
    ("Anna, the bedroom is ready, go there now.", ("go there now",)),
])
def test_they_are_read_as_asked(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
