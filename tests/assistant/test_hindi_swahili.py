"""Requests said partly in Hindi, Urdu, Punjabi, Swahili or Sheng (assistant/hindi.py,
assistant/swahili.py): what the reading makes of them, and what stays talk."""

from __future__ import annotations

import pytest

from robovoice.assistant.hindi import from_hindi
from robovoice.assistant.intent import read_request
from robovoice.assistant.reading import ClauseKind
from robovoice.assistant.swahili import from_swahili


@pytest.mark.parametrize(("said", "english"), [
    ("Arre beta, kitchen tak jao zara, jaldi jaldi.", "Arre, go to the kitchen, quickly."),
    ("Pehle projector chalao, phir Anna ko video call milao.", "first turn on the projector, then call Anna."),
    ("Saath wali Clara ko video pe bulao.", "call Clara."),
    ("Yeh call khatam karo aur phir Doctor Weber sahib ko milao.", "end the call then call Doctor Weber."),
    ("Ruk ja, ruk ja! Udhar nahin, wapas kitchen aa ja.", "stop, stop! not there, go back to the kitchen."),
    ("Anna nu video wala phone la de puttar.", "call Anna."),  # Punjabi
    ("Call na kaatna beta.", "don't end the call."),
    ("Ben ko abhi call mat karo.", "don't call Ben."),
    ("Doctor ko bhi call kar sakte ho tum?", "can you call Doctor?"),
    ("Rasoi mein jao, phir darwaze pe jao.", "go to the kitchen, then go to the front door."),
    # needs and goings-on are not asked: "I have to go to the bathroom", "she is going home"
    ("Mujhe bathroom jaana hai.", "Mujhe bathroom jaana hai."),
    ("Woh ghar ja rahi hai.", "Woh ghar ja rahi hai."),
    ("living room bohot thanda hai aaj kal.", "living room bohot thanda hai these days."),
    # said to someone by name: left as said
    ("Imran beta, projector band kar do.", "Imran beta, turn off the projector."),
    # no Hindi word: nothing changed ("to", "par", "me" are English)
    ("Go to the kitchen, par for the course.", "Go to the kitchen, par for the course."),
])
def test_hindi_urdu_and_punjabi_requests_are_put_in_english(said: str, english: str) -> None:
    assert from_hindi(said) == english


@pytest.mark.parametrize(("said", "english"), [
    ("Maze Jarvis, piga simu Uncle Ben, nataka kumwitisha fare ya matatu.", "Jarvis, call Ben,."),
    ("Zima projector, alafu uende kitchen. Ni hayo tu.", "turn off the projector, then go to the kitchen. that's all."),
    ("Sasa, kata hiyo call, then uende ukachaji.", "end the call, then go charge."),
    ("Tafadhali nenda jikoni, kisha mpigie simu Clara.", "please go to the kitchen, then call Clara."),
    ("Bro, chill kwa hallway hapo, usiblock mlango wa kitchen.",
     "go and wait in the hallway, don't block mlango wa kitchen."),
    ("Usipige simu Anna sasa hivi, amelala.", "don't call Anna now,."),
    ("Jarvis, usikate simu, Anna is still talking.", "Jarvis, don't end the call, Anna is still talking."),
    ("Unaweza kuwasha projector?", "can you turn on the projector?"),
    ("Wewe, unaweza kuongea na watu kwa video?", "Wewe, are you able to ongea na watu kwa video?"),
    ("Niaje Jarvis, uko wapi saa hii?", "Jarvis, where are you now?"),
    ("usisimame, endelea tu.", "don't stop, keep going."),
    # English that looks Swahili stays as said
    ("I'm still using it, Sana.", "I'm still using it, Sana."),
])
def test_swahili_and_sheng_requests_are_put_in_english(said: str, english: str) -> None:
    assert from_swahili(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("Projector bujha do, phir bedroom chalo, aur wahan pohonch ke Anna ko call karo.",
     ("turn off the Projector", "go to the bedroom", "call Anna")),
    ("Manze, go to the living room, washa projector, then unipigie Ben, nataka kumwonyesha goal ya jana.",
     ("go to the living room", "turn on the projector", "call Ben")),
    ("Uende hallway kwanza, halafu front door.", ("go to the hallway first", "front door")),
    ("Abhi Anna ko call mat karna, woh kaam pe hai.", ()),
    ("Projector baad mein lagana, pehle sab khana kha lein.", ()),
    ("Usiende kitchen sasa, the floor is wet.", ()),
    ("Usichaji bado, bro, nataka ukae hapa kwanza.", ()),
    ("Doctor ko bhi call kar sakte ho tum? Bas pooch rahi hoon, abhi nahin.", ()),
])
def test_a_request_said_partly_in_hindi_or_swahili_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text tests v82 and v83: these were talk (nothing done), did one thing, or (the "na kaatna",
    don't cut the call) started a call."""
    assert tuple(read_request(text).worded_steps) == steps


def test_an_ability_question_in_swahili_asks_nothing() -> None:
    kinds = {c.kind for c in read_request("Wewe, unaweza kuongea na watu kwa video?").clauses}
    assert ClauseKind.REQUEST not in kinds and ClauseKind.ABILITY in kinds


@pytest.mark.parametrize(("text", "steps"), [
    # text test v84: "… karne se pehle" (before doing …), Punjabi "wal chal" and "te othon" (then, from
    # there), "X pe jaake dekho" (go and look), "aur sab ho jaye toh" (once that's done)
    ("Clara aunty ko call karne se pehle projector off kar do.", ("turn off the projector", "call Clara")),
    ("Bedroom wal chal, te othon Ben nu phone kar.", ("go to the Bedroom", "call Ben")),
    ("Hallway pe jaake dekho.", ("go to the Hallway", "check")),
    ("Living room jao, projector chalu karo, aur sab ho jaye toh dock pe wapas aa jana.",
     ("go to the Living room", "turn on the projector", "go back to the charging dock")),
    ("Ruk ja! Te fer apne charging dock te wapas chala ja.", ("stop", "go back to the charging dock")),
    # text test v85: "kabla ya ku…" (before …), "ukishafika X" (once you're in X), "ila kwanza" (but first)
    ("Kabla ya kunipigia Ben, kwanza enda hallway.", ("first go to the hallway", "call Ben")),
    ("Ukishafika sebuleni, mpigie Dr. Weber.", ("go to the living room", "call Dr. Weber")),
    ("Mpigie daktari Weber, ila kwanza uje bedroom nilipo.", ("first come to the bedroom where I am", "call Weber")),
    ("Aje, si kitchen bana, geuza uende bedroom.", ("go to the bedroom",)),
    # taken back, or put off
    ("Ben ko call kar do... nahi, ruko, rehne do, woh abhi so raha hoga.", ()),
    ("Washa projector... aa, hapana, achana nayo, macho yananiuma leo.", ()),
    ("Ngoja kwanza, baada ya chakula cha mchana ndio urudi kwenye dock.", ()),
    ("can u like, play netflix on that projector or nah", ()),
])
def test_what_the_first_runs_of_v84_and_v85_missed_is_read(text: str, steps: tuple[str, ...]) -> None:
    assert tuple(read_request(text).worded_steps) == steps


@pytest.mark.parametrize(("text", "steps"), [
    # text test v86: Urdu's courtesy ("tashreef le jaiye"), the verb before its negation ("rukiye mat"),
    # "X check karo", "wapas X aake …", "X ki taraf ho aaiye", "kitchen nahin" (not the kitchen)
    ("Miyan, zara kitchen tak tashreef le jaiye.", ("go to the kitchen",)),
    ("Rukiye mat, chalte rahiye; main to bas khaans raha tha.", ()),
    ("Haan suno, pehle front door check karo, phir wapas living room aake projector on kar dena.",
     ("first go check the front door", "go to the living room", "turn on the projector")),
    ("Dock par jaane se pehle zara bathroom ki taraf ho aaiye.", ("go to the bathroom", "go to the charging dock")),
    ("Arey, kitchen nahin bhai, bedroom ki taraf mudiye.", ("go to the bedroom",)),
    ("Anna beti se video call milaiye.", ("call Anna",)),
    # text test v87: "projekta", "naomba u…", "iwashe", "ukate hii call", "wacha tu, si lazima"
    ("Zima projekta, tafadhali.", ("turn off the projector",)),
    ("Naomba umpigie binti yangu Anna.", ("please call my daughter Anna",)),
    ("Manze, zima projector na ukate hii call, tumemaliza.", ("turn off the projector", "end the call")),
    ("Enda bedroom... aah, wacha tu, si lazima.", ()),
    ("Tafadhali fanya hivi: kwanza uzime projekta, pili uende korido, na mwisho umpigie Ben.",
     ("please first turn off the projector", "go to the hallway", "finally call Ben")),
])
def test_what_the_first_runs_of_v86_and_v87_missed_is_read(text: str, steps: tuple[str, ...]) -> None:
    assert tuple(read_request(text).worded_steps) == steps


@pytest.mark.parametrize(("said", "steps"), [
    # Gujarati, which shares most of Hindustani's turns (text test v132); made up here
    ("Kitchen ma jao, beta.", ("go to the Kitchen",)),
    ("Anna ne video call karo.", ("call Anna",)),
    ("Bedroom ma jaine ubho re, I am coming.", ("go to the Bedroom",)),
    ("Aavjo, hang up now. Then projector bandh.", ("hang up now", "projector off")),
    ("Pehla hallway, pachhi kitchen.", ("go to the hallway", "kitchen")),
    ("Now kitchen, then the bedroom.", ("Now kitchen", "the bedroom")),
])
def test_gujarati_is_read_as_english_says_it(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).worded_steps == steps
