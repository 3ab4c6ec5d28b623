"""A request taken back by a "don't" with its own verb, a time said alone after it, a room said
with no article, a correction said before its "not the X", a request passed on with "says … now",
and a home-to-charge step (`neighbours`, `order_words.puts_off`, `clauses`, `clause_kind`): plain
code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "steps"), [
    # the same verb, said with a "don't": the request is taken back, and the "wait" before it is a pause
    ("Ring Clara. Hang on, don't ring her yet.", ()),
    ("Phone Ben. Sorry, wait wait, don't call anyone just now.", ()),
    ("Head to the garage. No, don't go anywhere.", ()),
    # … but another name, or a way to go, takes back nothing
    ("Ring Clara, don't ring Ben.", ("Ring Clara",)),
    ("Go to the garage and don't go through the hall", ("Go to the garage",)),
    # a time said alone after a request puts it off; a time said with a request of its own does not
    ("Ring Clara... later. Not now. Tonight.", ()),
    ("Go to the garage. Later, ring Clara.", ("Go to the garage",)),
    ("Go to the garage. Later, the lounge.", ("Go to the garage",)),
])
def test_a_request_taken_back_or_put_off(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


@pytest.mark.parametrize(("said", "steps"), [
    ("Once you are in bedroom, ring Clara.", ("go to bedroom", "ring Clara")),
    ("Once you are in trouble, ring Clara.", ("ring Clara",)),  # no room
    ("Oh dear, I said it wrong. KITCHEN, not bedroom.", ("KITCHEN",)),
    ("The lounge, not the kitchen, is where I left my keys.", ("is where I left my keys",)),  # no drive
    ("Lounge first, then home to charge.", ("Lounge first", "home to charge")),
    ("I went home to charge my phone.", ()),
    ("Grandpa says switch the projector off now.", ("switch the projector off now",)),
    ("The nurse says go to bed early.", ()),  # advice, with no now
    ("Ring Clara, and after you've done that go to the lounge.", ("Ring Clara", "go to the lounge")),
    ("After you finish this call with Clara ring Ben", ("finish this call with Clara", "ring Ben")),
])
def test_rooms_corrections_relays_and_order(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
