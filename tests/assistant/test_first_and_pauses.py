""""…, but first, …" after requests, a "wait" said between requests, a room said alone first, the
person a sentence is about, an exclamation with "look", and Cantonese "no need" and "later"
(`intent`, `neighbours`, `addressee`, `clause_kind`, `code_switch`): plain code, no model. The
utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "steps"), [
    # "first" said after requests puts what follows before them
    ("Ring Ben, but first, head to the lounge.", ("head to the lounge", "Ring Ben")),
    ("Ring Ben and turn the telly off, but first thing, go wait in the garage.",
     ("go wait in the garage", "Ring Ben", "turn the telly off")),
    ("Go to the garage. First, though, ring Ben.", ("ring Ben", "Go to the garage")),
    ("First, go to the garage, then ring Ben.", ("go to the garage", "ring Ben")),  # first already
    ("Garage first to fetch the post, then the lounge.", ("Garage first to fetch the post", "the lounge")),
    ("Once you get into the bedroom, ring Ben.", ("go to the bedroom", "ring Ben")),
    ("Into the lounge you'll go, I left my book there.", ("go Into the lounge",)),
    # a "wait" between a request and more words is a pause; one said last is still asked
    ("Ring Ben. Oh, wait, before that go to the garage.", ("go to the garage", "Ring Ben")),
    ("Go to the garage. Wait!", ("Go to the garage", "Wait")),
    # a room alone, then a request: the first step; not before its own drive ("Lounge. Go.")
    ("Lounge. Telly off.", ("Lounge", "Telly off")),
    ("Kitchen. Is the kettle on?", ("Is the kettle on",)),
])
def test_the_order_and_the_pauses_of_what_is_asked(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


@pytest.mark.parametrize(("said", "steps"), [
    ("My back again... Doctor Weber, I want to talk to him. Ring him please.",
     ("I want to talk to him", "Ring him please")),
    ("Go to the garage. Ben, give her the remote.", ("Go to the garage", "give her the remote")),
    ("Clara, love, look how lovely the lounge looks!", ()),  # an exclamation, said to Clara
    ("Go charge? Mh sai, the battery is fine.", ()),  # Cantonese: no need
    ("Ring Ben... yat jan sin.", ()),  # Cantonese: in a while
    ("Garage, then ring Ben, hai mai?", ("Garage", "ring Ben")),  # a tag: right?
])
def test_who_it_is_about_exclamations_and_cantonese(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps
