"""A message texted with no full stops, "lol" between sentences, "+" for "and" and the "I" left off
(assistant/texting.py, with `lexicon.plain`), and turns of Irish English read with them: plain
code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

import pytest

from robovoice.assistant.intent import read_request
from robovoice.assistant.texting import from_texting


@pytest.mark.parametrize(("said", "english"), [
    ("done chatting to clara you can end it now", "done chatting to clara. you can end it now"),
    ("im off so you can charge now", "im off so you can charge now"),  # a reason, not a sentence of its own
    ("turn the telly off + ring ben", "turn the telly off and ring ben"),
    ("thats enough clara time lol hang up", "thats enough clara time. hang up"),
    ("need you in the garage asap", "I need you in the garage asap"),
    ("ok really need you to ring ben", "ok I really need you to ring ben"),
    ("Ben needs you in the garage", "Ben needs you in the garage"),
    ("garage please he wants you", "garage please. he wants you"),
])
def test_a_texted_message_gets_its_sentences_and_subject_back(said: str, english: str) -> None:
    assert from_texting(said) == english


@pytest.mark.parametrize(("said", "steps"), [
    ("ok im done talking to clara u can hang up now ty", ("you can hang up now thank you",)),
    ("facetime ben for me my hands r full", ("facetime ben for me my hands are full",)),
    ("ring clara after u get to the lounge pls", ("go to the lounge", "ring clara")),
    ("Into the garage with you, and then ring Ben.", ("Into the garage with you", "ring Ben")),
    ("Let Clara go now and ring Ben.", ("end the call with Clara now", "ring Ben")),
    ("Let Ben go to the garage", ("Let Ben go to the garage",)),  # not the call's end
    ("Finish with Anna now, and after, go and charge.", ("end the call with Anna now", "go charge")),
    ("I'll finish with Anna's photos later.", ()),
    ("Mamgu, the projector on this thing is decent, isn't it.", ()),  # "on this thing": no state
    ("Go to the lounge please", ("Go to the lounge please",)),
    # a remark on the job after it is no step of its own
    ("go to the kitchen then call anna. easy", ("go to the kitchen", "call anna")),
    ("Hallway, then ring Ben. Cheers x", ("Hallway", "ring Ben")),
])
def test_texted_and_irish_requests_are_read_as_asked(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


def test_an_end_before_a_room_is_speech_to_texts_then() -> None:
    """Audio test v112: "…, then the front door, …" came out "…, end the front door, …"."""
    assert read_request("go to the hallway, end the front door, and call Anna.").steps == (
        "go to the hallway", "the front door", "call Anna")
    assert read_request("End the call, then the kitchen.").steps == ("End the call", "the kitchen")
    # "head for the hallway" as "end for the hallway" (audio test v121)
    assert read_request("Switch the projector off, and end for the bedroom.").steps == (
        "Switch the projector off", "head for the bedroom")
