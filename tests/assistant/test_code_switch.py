"""Requests said partly in Spanish or Hindi inside English speech (assistant/code_switch.py)."""

from __future__ import annotations

import pytest

from robovoice.assistant.code_switch import in_english
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "english"), [
    ("prende el projector", "turn on the projector"),
    ("Apaga el proyector, por favor.", "turn off the projector, please."),
    ("Ve a la cocina primero, después al hallway.", "go to the kitchen first, then to the hallway."),
    ("Ve al cuarto", "go to the bedroom"),  # one "the", not two
    ("Regresa a la sala y luego llama a Anna.", "go back to the living room and then call Anna."),
    ("Turn on the projector y llama a Ben", "Turn on the projector and call Ben"),
    ("Projector band karo", "turn off the Projector"),
    ("Light band karo", "Light off"),
    # English words that look like the Spanish ones stay as they are
    ("I've got a llama at the farm", "I've got a llama at the farm"),
    ("The sala is my favourite room", "The sala is my favourite room"),  # no Spanish request said
    ("Call Al and then go to the kitchen", "Call Al and then go to the kitchen"),
    ("No apagues el projector", "don't turn off el projector"),  # a Spanish "don't": an English one, no request
])
def test_spanish_and_hindi_requests_are_put_in_english(said: str, english: str) -> None:
    assert in_english(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("Turn on the projector y después llama a Ben, he wants to see.", ("Turn on the projector", "call Ben")),
    ("Go to the bedroom, prende el projector, and then call Ben.",
     ("Go to the bedroom", "turn on the projector", "call Ben")),
    ("Primero ve al baño, después enciende el projector.", ("first go to the bathroom", "turn on the projector")),
    ("Ay, robot, go to the bathroom un momentito, my glasses are in there.", ("go to the bathroom quickly",)),
    ("No llames a Ben todavía.", ()),  # "don't call Ben yet"
    ("No apagues el projector, mija.", ()),
])
def test_a_request_said_partly_in_spanish_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v69: a home-help's "Ve a la cocina primero, después al hallway", "… y después
    llama a Ben", "prende el projector" were talk, and those steps were never done."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("said", "english"), [
    ("Pakipatay po ng projector, salamat po.", "please turn off the projector, thanks."),
    ("Pumunta ka sa kusina, tapos tawagan mo si Ben.", "go to the kitchen, then call Ben."),
    ("ibaba mo na yung tawag tas balik ka sa charger, pagod na ako", "end the call then go back to the charger,"),
    ("call mo si Tita Clara, salamat", "call Clara, thanks"),
    ("Punta ka sa sala... wait, never mind, dyan ka lang.", "go to the living room... wait, never mind, stay there."),
    ("The sala is lovely at night", "The sala is lovely at night"),  # no word only Tagalog has: as said
])
def test_taglish_requests_are_put_in_english(said: str, english: str) -> None:
    assert in_english(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("Kuya, punta ka po sa sala tapos buksan mo yung projector, salamat po.",
     ("go to the living room", "turn on the projector")),
    ("Wag mo munang buksan ang projector, mamaya na lang.", ()),
    ("call mo si Clara tas punta ka sa front door, andun na daw siya", ("call Clara", "go to the front door")),
])
def test_a_taglish_request_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v75: "pakibukas po yung projector", "punta ka sa sala tapos buksan mo …" were
    talk; a Tagalog aside after a request ("andun na daw siya") was one more thing asked."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("said", "english"), [
    ("Pa-off mo na yung projector, inaantok na ako.", "turn off the projector,."),
    ("Dun ka muna sa kusina, tapos sa banyo naman.", "go to the kitchen, then go to the bathroom."),
    ("Bago ka bumalik sa charger, i-video call mo muna si Clara.",
     "before you go back to the charger, video call Clara."),
    ("Para! Dyan ka lang muna.", "stop! stay there first."),
    ("Pagdating mo sa sala, pakibukas agad ng projector.",
     "when you get to the living room, please turn on the projector."),
    ("para makapag-usap tayo", "para makapag-usap tayo"),  # no word only Tagalog has: as said
])
def test_more_taglish_requests_are_put_in_english(said: str, english: str) -> None:
    assert in_english(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("Dun ka muna sa kusina, tapos sa banyo naman.", ("go to the kitchen", "go to the bathroom")),
    ("Bago ka bumalik sa charger, i-video call mo muna si Clara.", ("video call Clara", "go back to the charger")),
    ("Kaya mo bang tumawag mag-isa kay Ben, o tutulungan pa kita?", ()),
    ("Pagdating mo sa sala, pakibukas agad ng projector.", ("go to the living room", "please turn on the projector")),
])
def test_more_taglish_requests_are_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v76: "pa-on", "dun ka na lang sa sala", "silipin mo sa front door", "i-video call
    mo si Anna", "tapos sa kusina", "bago mo tawagan si Clara, …" and "pagdating mo sa …" were
    talk or did one step; "kaya mo bang … mag-isa, o …?" (by yourself, or …?) switched on."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Halika dito sa kusina, may ipapakita ako sa'yo.", ("come to the kitchen",)),
    ("Una, patayin mo ang projector, dayon balik ka sa charger.", ("turn off the projector", "go back to the charger")),
    ("Tawagan mo si Tita Anna... ay hindi pala, mamaya na.", ()),
    ("Pumunta ka sa banyo, pero bago 'yon, i-on mo ang projector.", ("turn on the projector", "go to the bathroom")),
    ("Dun ka sa may pasilyo, hinihintay kita.", ("go to the hallway",)),
    ("Head to the kitchen. Oh, no actually, stay here with me.", ()),
    ("Just a mo, I'll be there.", ()),  # English "a mo": no Tagalog
])
def test_taglish_with_bisaya_and_batangas_words_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v78: "halika rine sa sala", "dun ka sa may pintuan sa harap", Bisaya "dayon",
    "unya", "ug", "pero bago 'yon, …" (but before that) were talk or out of order, and "…, ay,
    hindi pala, diyan ka na lang" (no, actually: stay there) drove."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Saka mo na buksan ang projector, kumakain pa kami.", ()),
    ("Pumaroon ka sa kusina at nang makita ko kung may tubig pa.", ("go to the kitchen",)),
    ("Paandarin mo 'yung projector tsaka i-FaceTime mo si Mommy Clara.",
     ("turn on the projector", "video call Mommy Clara")),
    ("Pa-end na ng call, salamat.", ("end the call",)),
    ("Sige, ibaba mo na yung tawag at saka ka na mag-charge.", ("end the call", "go charge")),  # and then
    ("Marunong ka bang mag-video call sa Dubai?", ()),  # knows how: an ability asked (reading diff)
])
def test_quezon_city_taglish_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v80: "saka ka na pumunta sa may pinto" (go there later) drove; "pumaroon",
    "magtungo", "paandarin", "kontakin", "i-FaceTime", "pa-end", "tsaka" were not words the
    reading knew."""
    assert read_request(text).worded_steps == steps
