"""Does an action fit what was asked (`assistant.fit`), with the words the sim robot's own
manifests declare: plain code, no model. The utterances are made up here, not eval cases."""

from __future__ import annotations

from pathlib import Path

import pytest

from robovoice.assistant.fit import claimed_elsewhere, fits, fitting_tools, listed_names, stem, unsaid
from robovoice.assistant.gate import NOT_REQUESTED, OTHER, UNCLEAR, own_words, refusal
from robovoice.assistant.intent import read_request
from robovoice.assistant.lexicon import words
from robovoice.llm.base import ToolSpec
from robovoice.manifest.loader import load_manifest_dir
from robovoice.manifest.voice import VoiceDecl

MANIFESTS = Path(__file__).parents[2] / "src" / "robovoice" / "sim" / "manifests"


def _sim_voice() -> dict[str, VoiceDecl]:
    loaded = load_manifest_dir(MANIFESTS)
    return {tool.name: tool.voice for item in loaded.manifests.values() for tool in item.manifest.tools
            if tool.voice is not None}


def _sim_specs() -> dict[str, ToolSpec]:
    loaded = load_manifest_dir(MANIFESTS)
    return {tool.name: ToolSpec(tool.name, tool.description, tool.parameters or {})
            for item in loaded.manifests.values() for tool in item.manifest.tools}


VOICE = _sim_voice()
SPECS = _sim_specs()
WORDS = {name: section.words for name, section in VOICE.items()}


@pytest.mark.parametrize(("word", "same"), [
    ("charged", "charge"), ("charging", "charger"), ("plugged", "plug"), ("calling", "call"), ("rings", "ring"),
    ("going", "go"), ("phoned", "phone"), ("stopped", "stop"), ("docking", "dock"),
])
def test_a_words_forms_share_its_stem(word: str, same: str) -> None:
    assert stem(word) == stem(same)


@pytest.mark.parametrize(("word", "other"), [("call", "cal"), ("go", "good"), ("ring", "bring"), ("end", "ends up")])
def test_different_words_keep_different_stems(word: str, other: str) -> None:
    assert stem(word) != stem(other)


@pytest.mark.parametrize(("text", "tool", "arguments"), [
    ("Go and get yourself plugged in, it's late.", "return_to_dock", {}),
    ("Give my daughter a ring, would you?", "start_video_call", {"contact": "Anna"}),
    ("Put the doctor on, please.", "start_video_call", {"contact": "Dr. Weber"}),  # the argument, said aloud
    ("Could you nip through to the bedroom?", "navigate_to", {"target": "bedroom"}),
    ("That light on the wall is too bright, switch it off.", "set_projector_power", {"on": False}),  # "it"
    ("Right, we're done, hang up now.", "end_video_call", {}),
])
def test_a_request_in_everyday_words_fits_its_tool(text: str, tool: str, arguments: dict[str, object]) -> None:
    assert fits(read_request(text), tool, WORDS[tool], arguments)


@pytest.mark.parametrize(("text", "tool", "arguments", "meant"), [
    ("Go and get yourself plugged in, it's late.", "set_projector_power", {"on": True},
     ["navigate_to", "return_to_dock"]),
    ("Pop to the porch and see who knocked.", "start_video_call", {"contact": "Anna"}, ["navigate_to"]),
    ("Tell me your battery, then wander to the bathroom.", "return_to_dock", {}, ["navigate_to"]),
    ("Switch the projector on.", "start_video_call", {"contact": "Ben"}, ["set_projector_power"]),
])
def test_a_tool_beside_a_request_for_another_does_not_fit(
        text: str, tool: str, arguments: dict[str, object], meant: list[str]) -> None:
    intent = read_request(text)
    assert not fits(intent, tool, WORDS[tool], arguments)
    assert fitting_tools(intent, WORDS, tool) == meant


@pytest.mark.parametrize(("text", "contact", "fit"), [
    ("Tell Ben the plumber is coming.", "Ben", False),  # a message names him; nobody asked to ring him
    ("Let Clara know the parcel came.", "Clara", False),
    ("Say thanks to Anna from me, and hang up.", "Anna", False),
    ("Tell Ben to ring me back, call him now.", "Ben", True),  # the call is asked for in its own words
    ("Give Ben a ring and tell him tea's ready.", "Ben", True),
])  # fmt: skip
def test_a_message_for_somebody_does_not_ask_to_call_them(text: str, contact: str, fit: bool) -> None:
    assert fits(read_request(text), "start_video_call", WORDS["start_video_call"], {"contact": contact}) is fit


@pytest.mark.parametrize(("text", "tool", "arguments", "fit"), [
    ("Open the door, please.", "navigate_to", {"target": "front door"}, False),
    ("Could you lock the back door?", "navigate_to", {"target": "front door"}, False),
    ("Tidy the kitchen.", "navigate_to", {"target": "kitchen"}, False),
    ("Go and open the front door.", "navigate_to", {"target": "front door"}, True),
    ("The front door, please.", "navigate_to", {"target": "front door"}, True),
    ("Close the call now.", "end_video_call", {}, True),
])
def test_a_verb_done_with_hands_to_a_place_does_not_ask_to_go_there(
        text: str, tool: str, arguments: dict[str, object], fit: bool) -> None:
    assert fits(read_request(text), tool, WORDS[tool], arguments) is fit


def test_a_filler_before_another_tools_words_does_not_hide_them() -> None:
    intent = read_request("ok wrap up the call with Anna, then go to the kitchen")
    assert fits(intent, "end_video_call", WORDS["end_video_call"], {})
    rivals = [WORDS["end_video_call"]]
    assert not fits(intent, "start_video_call", WORDS["start_video_call"], {"contact": "Anna"}, rivals=rivals)


def test_a_word_of_a_gloss_of_several_words_names_nothing_alone() -> None:
    """Text test v47: "Can you make a video call to my family …?" called Dr. Weber, glossed
    "family doctor"; the gloss's last word names him, and the whole gloss."""
    spec = SPECS["start_video_call"]
    call = {"contact": "Dr. Weber"}
    assert unsaid(spec.description, spec.parameters, call, words("ring my family")) == ["Dr. Weber"]
    assert unsaid(spec.description, spec.parameters, call, words("ring the doctor")) == []
    assert unsaid(spec.description, spec.parameters, call, words("ring the family doctor")) == []


def test_lets_see_if_you_can_is_no_message_but_let_anna_know_is() -> None:
    """Dev `letssee-1`: "let" opened the clause, so it read as a message ("let Anna know …")
    and the place named in it did not fit the drive."""
    drive = ("navigate_to", WORDS["navigate_to"], {"target": "bathroom"})
    assert fits(read_request("Let's see if you can make your own way to the bathroom."), *drive)
    call = ("start_video_call", WORDS["start_video_call"], {"contact": "Anna"})
    assert not fits(read_request("Let Anna know I'm fine."), *call)


def test_a_word_said_only_inside_another_word_does_not_fit() -> None:
    assert not fits(read_request("Bring the blanket to the bedroom."), "start_video_call", WORDS["start_video_call"],
                    {"contact": "Ben"})


def test_a_tool_that_declares_no_words_is_not_checked() -> None:
    assert fits(read_request("Wave at the cat."), "open_gripper", (), {})


def test_a_yes_to_the_robots_own_question_is_read_with_the_conversation() -> None:
    said = {"shall", "i", "call", "anna"}
    call = ("start_video_call", WORDS["start_video_call"], {"contact": "Anna"})
    assert fits(read_request("Yes please.", answering=True), *call, said)
    assert not fits(read_request("Go to the kitchen."), *call, said)  # not an answer: earlier words do not count


def test_the_gate_refuses_a_tool_nobody_asked_for_and_names_what_fits() -> None:
    spec = ToolSpec("set_projector_power", "projector")
    body = refusal(read_request("You look tired, go and get yourself charged up."), spec, {"on": True}, (), VOICE)
    assert body is not None and body["error"] == NOT_REQUESTED and body["details"]["reason"] == OTHER
    assert "return_to_dock" in body["hint"]
    assert refusal(read_request("Turn the projector on."), spec, {"on": True}, (), VOICE) is None
    assert refusal(read_request("You look tired, go and charge."), spec, {"on": True}) is None  # no words known


@pytest.mark.parametrize(("text", "tool", "arguments", "missing"), [
    ("Get car on a video call.", "start_video_call", {"contact": "Anna"}, ["Anna"]),  # Clara, misheard
    ("Ring my sun.", "start_video_call", {"contact": "Dr. Weber"}, ["Dr. Weber"]),
    ("Ring my son.", "start_video_call", {"contact": "Ben"}, []),  # "Ben (son)" in the tool's description
    ("Could you ring the doctor?", "start_video_call", {"contact": "Dr. Weber"}, []),
    ("Give my neighbor a call.", "start_video_call", {"contact": "Clara"}, []),
    ("Go man.", "navigate_to", {"target": "kitchen"}, ["kitchen"]),  # garbled: nobody said a place
    ("Off to bed with you.", "navigate_to", {"target": "bedroom"}, []),  # "bed" begins "bedroom"
    ("Go and get yourself charged.", "navigate_to", {"target": "charging dock"}, []),
    ("Take me over to the, um, that room.", "navigate_to", {"target": "living room"}, ["living room"]),  # 3 rooms
    ("Go to the living room.", "navigate_to", {"target": "living room"}, []),
    ("Go to the door.", "navigate_to", {"target": "front door"}, []),  # the only door
    ("Go through to the front room.", "navigate_to", {"target": "front room"}, []),  # its own name, not listed
    ("Go to the room.", "navigate_to", {"target": "front room"}, ["front room"]),  # not all of it was said
    # the places' other names in navigate_to's description ("bathroom (loo, toilet, ...)")
    ("Pop to the loo for me.", "navigate_to", {"target": "bathroom"}, []),
    ("Go and wait in the lounge.", "navigate_to", {"target": "living room"}, []),
    ("Go through to the front room.", "navigate_to", {"target": "living room"}, []),  # a gloss said whole
    ("Go through to the front.", "navigate_to", {"target": "living room"}, ["living room"]),  # the front door too
    ("Wait by the entrance.", "navigate_to", {"target": "front door"}, []),
    ("Pop to the loo for me.", "navigate_to", {"target": "kitchen"}, ["kitchen"]),
])
def test_a_listed_argument_must_be_named_by_somebody(
        text: str, tool: str, arguments: dict[str, object], missing: list[str]) -> None:
    spec = SPECS[tool]
    assert unsaid(spec.description, spec.parameters, arguments, read_request(text).words()) == missing


def test_an_argument_named_earlier_in_the_conversation_counts_and_free_text_is_not_checked() -> None:
    spec = SPECS["start_video_call"]
    assert unsaid(spec.description, spec.parameters, {"contact": "Anna"}, ["call", "her", "anna"]) == []
    free = {"type": "object", "properties": {"text": {"type": "string"}}}
    assert unsaid("Say something.", free, {"text": "hello there"}, ["say", "hi"]) == []


def test_the_gate_asks_rather_than_calls_someone_nobody_named() -> None:
    spec = SPECS["start_video_call"]
    body = refusal(read_request("Get car on a video call, please."), spec, {"contact": "Anna"}, (), VOICE)
    assert body is not None and body["details"]["reason"] == UNCLEAR and "ask them" in body["hint"]
    assert own_words(body) == "Which one do you mean: Anna, Ben, Clara or Dr. Weber?"
    assert refusal(read_request("Get Clara on a video call, please."), spec, {"contact": "Clara"}, (), VOICE) is None
    there = refusal(read_request("Go over there."), SPECS["navigate_to"], {"target": "kitchen"}, (), VOICE)
    assert there is not None and own_words(there) == ("Which one do you mean: kitchen, living room, bedroom, "
                                                      "bathroom, hallway, front door or charging dock?")
    negated = refusal(read_request("Don't call Anna."), spec, {"contact": "Anna"}, (), VOICE)
    # nothing to choose: it was declined, and nothing else was said, so the robot's own line answers
    assert negated is not None and own_words(negated) == "All right, I won't."
    beside = refusal(read_request("Don't call Anna, call Ben."), spec, {"contact": "Anna"}, (), VOICE)
    assert beside is not None and own_words(beside) is None  # a request beside it: the model goes on


def test_an_ability_question_about_the_very_call_is_answered_yes_by_the_robot() -> None:
    call, dock, drive = SPECS["start_video_call"], SPECS["return_to_dock"], SPECS["navigate_to"]
    clara = refusal(read_request("Only curious - could you give Clara a ring?"), call, {"contact": "Clara"}, (), VOICE)
    assert clara is not None and own_words(clara) == "Yes, I can do that when you ask me to."
    charger = refusal(read_request("Are you able to get back on your charger alone?"), dock, {}, (), VOICE)
    assert charger is not None and own_words(charger) == "Yes, I can do that when you ask me to."
    # a contact nobody named, a place it never said, an "it" that is not what the call does: the model answers
    for text, spec, args in [("Could you phone people who live abroad?", call, {"contact": "Anna"}),
                             ("Could you make me a cup of tea?", drive, {"target": "kitchen"}),
                             ("If Ben rings while I'm out, could you answer it?", call, {"contact": "Ben"})]:
        body = refusal(read_request(text), spec, args, (), VOICE)
        assert body is not None and body["details"]["reason"] == "ability" and own_words(body) is None, text


def test_a_clause_that_opens_with_another_tools_words_does_not_fit_this_one() -> None:
    """Text test v15: "hang up the call" started a second call with Anna ("call" is a word of
    start_video_call's); the clause opens with end_video_call's words."""
    text = "I'm finished talking to Ben, so please hang up the call."
    body = refusal(read_request(text), SPECS["start_video_call"], {"contact": "Ben"}, (), VOICE)
    assert body is not None and body["details"]["reason"] == OTHER
    assert refusal(read_request(text), SPECS["end_video_call"], {}, (), VOICE) is None
    assert refusal(read_request("End this call and ring Clara."), SPECS["start_video_call"], {"contact": "Clara"},
                   (), VOICE) is None
    # the longer opening wins: "ring off" ends the call, though "ring" would start one (text test v48)
    ring_off = read_request("Turn the projector off, ring off from Ben, then go to the kitchen.")
    body = refusal(ring_off, SPECS["start_video_call"], {"contact": "Ben"}, (), VOICE)
    assert body is not None and body["details"]["reason"] == OTHER
    assert refusal(ring_off, SPECS["end_video_call"], {}, (), VOICE) is None
    assert refusal(read_request("Ring Ben."), SPECS["start_video_call"], {"contact": "Ben"}, (), VOICE) is None


def test_a_contact_named_in_the_correction_is_asked_for() -> None:
    """Text test v15: "Call Clara - … Ring Ben instead." refused Ben, as if the call itself were declined."""
    intent = read_request("Ring Ben - no, hold on, he's at work. Call Anna instead.")
    assert refusal(intent, SPECS["start_video_call"], {"contact": "Anna"}, (), VOICE) is None
    body = refusal(intent, SPECS["start_video_call"], {"contact": "Ben"}, (), VOICE)
    assert body is not None and body["details"]["reason"] == "negated"


def test_there_after_a_short_name_for_the_place_is_that_place() -> None:
    intent = read_request("Go down to the hall, and once you're there, give Ben a ring.")
    assert refusal(intent, SPECS["navigate_to"], {"target": "hallway"}, (), VOICE) is None


def test_a_pause_in_a_correction_does_not_fit_the_stop() -> None:
    intent = read_request("Head over to the kitchen - no, wait, the bedroom.")
    body = refusal(intent, SPECS["stop_robot"], {}, (), VOICE)
    assert body is not None and body["details"]["reason"] == OTHER


def test_there_refers_to_a_place_named_by_another_of_its_names() -> None:
    """Text test v16: "...a drip in the loo. Could you nip in there and have a look?" The drive
    to the bathroom was refused as referring to nothing: only the sim knew "loo"."""
    text = "I think there's a drip in the loo. Could you nip in there and have a look?"
    assert refusal(read_request(text), SPECS["navigate_to"], {"target": "bathroom"}, (), VOICE) is None
    body = refusal(read_request("Could you nip in there and have a look?"), SPECS["navigate_to"],
                   {"target": "bathroom"}, (), VOICE)
    assert body is not None and body["details"]["reason"] == "unclear"


def test_a_places_other_name_fits_its_drive_whatever_the_verb() -> None:
    """Dev alias-1 (text test v18: "Would you trundle out to the hall for me?" was refused: no
    declared verb, and "hall" is not "hallway")."""
    text = read_request("Would you sashay on down to the loo?")  # no declared verb
    assert refusal(text, SPECS["navigate_to"], {"target": "bathroom"}, (), VOICE) is None
    body = refusal(text, SPECS["navigate_to"], {"target": "kitchen"}, (), VOICE)
    assert body is not None and body["details"]["reason"] == OTHER


@pytest.mark.parametrize(("text", "tool", "arguments", "meant"), [
    ("Right, we've had our chat, you can halt the video now.", "stop_robot", {}, "end_video_call"),
    ("Stop the project, turn it on.", "stop_robot", {}, "set_projector_power"),  # a misheard "pop the projector on"
    ("Please plug the projector in.", "return_to_dock", {}, "set_projector_power"),
])
def test_a_word_for_a_tool_before_what_another_acts_on_does_not_fit_it(
        text: str, tool: str, arguments: dict[str, object], meant: str) -> None:
    """Dev audio (session 16): "Hey Jarvis, pop the projector on and then ring my son Ben"
    heard as "Stop the project, turn on and then ring my song, Ben." stopped the robot."""
    body = refusal(read_request(text), SPECS[tool], arguments, (), VOICE)
    assert body is not None and body["details"]["reason"] == OTHER
    assert meant in body["details"]["fits"]


@pytest.mark.parametrize("text", ["Stop the robot!", "Stop, the video can wait.", "Halt there, then ring Ben.",
                                  "Stop that!"])
def test_a_stop_of_the_robot_itself_still_fits(text: str) -> None:
    assert refusal(read_request(text), SPECS["stop_robot"], {}, (), VOICE) is None


NAMES = {name: listed_names(spec.description, spec.parameters) for name, spec in SPECS.items()}


@pytest.mark.parametrize(("text", "claimed"), [
    ("Could you put my son up on the screen for a chat?", True),  # "screen": the call's word too; Ben (son)
    ("Bring Clara up on the display, would you?", False),  # "display" is the projector's word only
    ("Put the screen on, then ring Anna.", False),  # the screen's clause names nobody
    ("Get the projector on the screen for Anna.", False),  # the projector's own name
    ("Put her on the screen, Clara I mean.", True),  # "her": someone the utterance names (text test v127)
    ("Put him on the screen.", False),  # nobody named: "him" is nobody the call lists
])
def test_a_word_two_tools_share_beside_a_value_one_lists_is_that_tools(text: str, claimed: bool) -> None:
    assert claimed_elsewhere(read_request(text), "set_projector_power", {"on": True}, WORDS, NAMES) is claimed


def test_the_gate_refuses_the_projector_for_a_call_on_the_screen() -> None:
    spec = SPECS["set_projector_power"]
    asked = read_request("Could you put my son up on the screen for a chat?")
    body = refusal(asked, spec, {"on": True}, (), VOICE, tools=list(SPECS.values()))
    assert body is not None and body["details"]["reason"] == OTHER and "start_video_call" in body["details"]["fits"]
    assert refusal(asked, SPECS["start_video_call"], {"contact": "Ben"}, (), VOICE, tools=list(SPECS.values())) is None


def test_a_drive_to_a_contact_is_refused_and_names_the_call() -> None:
    tools = list(SPECS.values())
    asked = read_request("Switch the projector on, then put my daughter up on it.")
    body = refusal(asked, SPECS["navigate_to"], {"target": "Anna"}, (), VOICE, tools=tools)
    assert body is not None and body["details"]["reason"] == OTHER and "start_video_call" in body["details"]["fits"]
    # a call to a place is left to the robot's own error: the model is not pointed at a drive
    assert refusal(read_request("Ring the bedroom."), SPECS["start_video_call"], {"contact": "bedroom"}, (), VOICE,
                   tools=tools) is None
    assert refusal(read_request("Go to Anna's room."), SPECS["navigate_to"], {"target": "Anna's room"}, (), VOICE,
                   tools=tools) is None


@pytest.mark.parametrize(("text", "said", "on", "runs"), [
    ("Turn that off... turn it off. And call Anna.", set(), False, True),
    ("Switch it off, please.", set(), False, True),
    ("Turn it on.", set(), True, False),  # on: a guess at what "it" is
    ("The telly's far too loud. Turn it off.", set(), False, False),  # "it" is the telly
    ("Turn it off.", {"telly", "loud"}, False, False),  # said before: the telly
])
def test_switching_it_off_with_nothing_named_is_the_one_thing_the_robot_switches(
        text: str, said: set[str], on: bool, runs: bool) -> None:
    refused = refusal(read_request(text), SPECS["set_projector_power"], {"on": on}, said, VOICE,
                      tools=list(SPECS.values()))
    assert (refused is None) is runs


def test_this_or_that_before_a_noun_names_it_and_points_back_to_nothing() -> None:
    """Text test v49: "Enough talking for today, Anna. Robot, you stop this call …" stopped the
    robot: "this" counted as a back reference, so every clause was searched, and the statement's
    "enough" fitted the stop. Before a noun it names the thing; alone or before "off" it points back."""
    text = "Enough talking for today, Anna, I am tired. Robot, you stop this call and put the projector off."
    body = refusal(read_request(text), SPECS["stop_robot"], {}, (), VOICE)
    assert body is not None and body["details"]["reason"] == OTHER
    assert refusal(read_request(text), SPECS["end_video_call"], {}, (), VOICE) is None
    said = read_request("The thing that throws pictures on the wall... turn that off.")
    assert refusal(said, SPECS["set_projector_power"], {"on": False}, (), VOICE) is None


def test_a_modal_after_the_thing_names_no_other_tool() -> None:
    """Text test v50: "the projector can go off now" did not fit the projector: "can", right
    after it, begins "cancel", as a misheard word may begin what it names."""
    intent = read_request("Right, the projector can go off now.")
    assert refusal(intent, SPECS["set_projector_power"], {"on": False}, (), VOICE) is None
    stop = refusal(read_request("Stop the call now."), SPECS["stop_robot"], {}, (), VOICE)
    assert stop is not None and stop["details"]["reason"] == OTHER


@pytest.mark.parametrize("text", [
    "Could you ring Clara, no, I mean Ben, and then go and wait by the front door?",
    "Go and wait for me in the bathroom, dear.",
])
def test_a_drive_to_wait_somewhere_is_no_stop(text: str) -> None:
    """Text test v20: "… and then go and wait by the front door" stopped the robot before the
    drive: its "wait" is what to do there; the drive's "go" opens the clause."""
    for tool in ("stop_robot", "cancel_navigation"):
        body = refusal(read_request(text), SPECS[tool], {}, (), VOICE)
        assert body is not None and body["details"]["reason"] == OTHER, (tool, body)
    assert refusal(read_request("Wait, stop, go back."), SPECS["stop_robot"], {}, (), VOICE) is None


def test_next_door_names_the_neighbour_not_the_front_door_and_a_picture_thing_is_the_projector() -> None:
    """Text test v58: "call Clara next door" let the drive to the front door through; "Switch that
    picture thing off" fitted no tool."""
    call = read_request("Could you call Clara next door?")
    tools = list(SPECS.values())
    assert refusal(call, SPECS["navigate_to"], {"target": "front door"}, (), VOICE, tools=tools) is not None
    assert refusal(call, SPECS["start_video_call"], {"contact": "Clara"}, (), VOICE, tools=tools) is None
    off = read_request("Switch that picture thing off.")
    assert refusal(off, SPECS["set_projector_power"], {"on": False}, (), VOICE, tools=tools) is None
    assert refusal(read_request("Take a picture of the hallway."), SPECS["set_projector_power"], {"on": True}, (),
                   VOICE, tools=tools) is not None


def test_bye_is_not_by_and_off_the_phone_ends_the_call() -> None:
    """"wait by the front door" let the end of a call through ("bye" and "by" shared a stem);
    "get off that phone" fitted no tool (text test v59)."""
    tools = list(SPECS.values())
    assert stem("bye") != stem("by")
    wait = read_request("Go and wait by the front door.")
    assert refusal(wait, SPECS["end_video_call"], {}, (), VOICE, tools=tools) is not None
    off = read_request("Get off that phone, then come into the kitchen.")
    assert refusal(off, SPECS["end_video_call"], {}, (), VOICE, tools=tools) is None


def test_kind_enough_to_is_courtesy_not_the_stops_enough() -> None:
    """Read again for text test v63: "Would you be good enough to call Ben?" let the robot's stop,
    the cancel and the end of a call through ("enough" is a word of each). Only the call fits."""
    said, tools = read_request("Would you be good enough to call Ben?"), list(SPECS.values())
    assert refusal(said, SPECS["start_video_call"], {"contact": "Ben"}, (), VOICE, tools=tools) is None
    for name in ("stop_robot", "cancel_navigation", "end_video_call"):
        body = refusal(said, SPECS[name], {}, (), VOICE, tools=tools)
        assert body is not None and body["details"]["reason"] == OTHER, name
    assert refusal(read_request("That's enough, stop."), SPECS["stop_robot"], {}, (), VOICE) is None


def test_a_bare_off_after_the_thing_is_named_fits_and_turn_it_off_is_no_stop() -> None:
    """Text test v65: "That projector has been humming … Off, please." did not fit the projector;
    "That's enough of that, turn it off. The call, I mean." ran the robot's stop ("enough", in a
    sentence "it" looked back to). The stop and the cancel fit only by a request's own words."""
    tools = list(SPECS.values())
    said = read_request("That projector has been humming all afternoon. Off, please.")
    assert refusal(said, SPECS["set_projector_power"], {"on": False}, (), VOICE, tools=tools) is None
    said = read_request("That's enough of that, turn it off. The call, I mean.")
    assert refusal(said, SPECS["end_video_call"], {}, (), VOICE, tools=tools) is None
    for name in ("stop_robot", "cancel_navigation"):
        body = refusal(said, SPECS[name], {}, (), VOICE, tools=tools)
        assert body is not None, name
    assert refusal(read_request("Enough! Stop it!"), SPECS["stop_robot"], {}, (), VOICE, tools=tools) is None


def test_the_doc_on_the_screen_is_the_call_and_it_looking_back_moves_nothing() -> None:
    """Text test v66: "Get us the doc on the screen, …" switched the projector on ("doc" named
    nobody), and "… front door sticks in the heat, give it a shove." drove ("it" pooled the door)."""
    tools = list(SPECS.values())
    said = read_request("Get us the doc on the screen, my knee's playing up.")
    assert refusal(said, SPECS["start_video_call"], {"contact": "Dr. Weber"}, (), VOICE, tools=tools) is None
    assert refusal(said, SPECS["set_projector_power"], {"on": True}, (), VOICE, tools=tools) is not None
    said = read_request("The front door sticks in the heat. Give it a shove.")
    assert refusal(said, SPECS["navigate_to"], {"target": "front door"}, (), VOICE, tools=tools) is not None


@pytest.mark.parametrize(("text", "contact"), [
    ("Let's wrap up the call with Anna now, and after that head into the bedroom.", "Anna"),
    ("Let's finish the call with Clara.", "Clara"),
])
def test_lets_before_the_ends_words_ends_the_call_and_starts_none(text: str, contact: str) -> None:
    """Text test v81: "Let's wrap up the call with Anna now, …" (in a call) started a call with
    her: the end's "wrap up" did not open the clause, "let's" did."""
    intent = read_request(text)
    body = refusal(intent, SPECS["start_video_call"], {"contact": contact}, (), VOICE, tools=list(SPECS.values()))
    assert body is not None and body["error"] == NOT_REQUESTED
    assert refusal(intent, SPECS["end_video_call"], {}, (), VOICE, tools=list(SPECS.values())) is None
    assert refusal(read_request(f"Let's call {contact}."), SPECS["start_video_call"], {"contact": contact}, (),
                   VOICE, tools=list(SPECS.values())) is None


@pytest.mark.parametrize(("text", "contact", "runs"), [
    # the call asked is the one the call's words name (text v95: the model rang Anna too)
    ("Hang up with Anna, then call Doctor Weber.", "Anna", False),
    ("Hang up with Anna, then call Doctor Weber.", "Dr. Weber", True),
    ("End the call with Anna and ring Ben.", "Anna", False),
    # both named in requests to call: both run
    ("Call Anna, and ring Ben after.", "Anna", True),
    ("Call Anna, and ring Ben after.", "Ben", True),
    ("Hang up on Ben, then ring Clara for me.", "Clara", True),
])
def test_a_call_named_only_in_the_request_to_end_one_is_not_asked(text: str, contact: str, runs: bool) -> None:
    body = refusal(read_request(text), SPECS["start_video_call"], {"contact": contact}, (), VOICE,
                   tools=list(SPECS.values()))
    assert (body is None) is runs
    assert runs or (body is not None and body["details"]["reason"] == OTHER)


@pytest.mark.parametrize(("text", "runs"), [
    # a request that opens with the call's verb asks no end, whoever it names (the end's noun "call" is no verb)
    ("Call the plumber.", False),
    ("Call my sister and tell her we're late.", False),
    # the end's own words, or its noun before its verb as Hindi says it, still ask it
    ("End the call.", True),
    ("Call end karo, I'm tired.", True),
])
def test_a_call_to_someone_unknown_asks_no_end(text: str, runs: bool) -> None:
    body = refusal(read_request(text), SPECS["end_video_call"], {}, (), VOICE, tools=list(SPECS.values()))
    assert (body is None) is runs


@pytest.mark.parametrize("text", ["Put the picture box on.", "Turn the picture gadget on, the one on the wall."])
def test_a_word_searched_for_is_the_declared_thing(text: str) -> None:
    # "picture thing" is declared: "picture box", "picture gadget" are the same thing, said while searching for the word
    assert refusal(read_request(text), SPECS["set_projector_power"], {"on": True}, (), VOICE,
                   tools=list(SPECS.values())) is None


def test_a_place_said_alone_names_the_drive_when_another_call_is_refused() -> None:
    """Text test v111: "Front door, quickly, somebody is ringing!" and the model rang Anna; told
    only that nobody asked for the call, it did nothing. The refusal names the drive, which the
    place alone asks for."""
    asked = read_request("Bedroom, quick, the phone's ringing!")
    body = refusal(asked, SPECS["start_video_call"], {"contact": "Anna"}, (), VOICE, tools=list(SPECS.values()))
    assert body is not None and body["details"]["reason"] == OTHER and body["details"]["fits"] == ["navigate_to"]
    assert "fits navigate_to" in body["hint"]


def _runs(text: str, tool: str, arguments: dict[str, object]) -> bool:
    return refusal(read_request(text), SPECS[tool], arguments, (), VOICE, tools=list(SPECS.values())) is None


def test_a_name_said_last_is_no_call_and_one_call_names_its_person() -> None:
    assert _runs("Go to the kitchen, Ben.", "navigate_to", {"target": "kitchen"})
    assert not _runs("Go to the kitchen, Ben.", "start_video_call", {"contact": "Ben"})
    assert _runs("Call Clara, Ben.", "start_video_call", {"contact": "Clara"})
    assert not _runs("Call Clara, Ben.", "start_video_call", {"contact": "Ben"})  # (audio test v102)
    assert _runs("Ring my son", "start_video_call", {"contact": "Ben"})
