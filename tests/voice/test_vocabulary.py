"""Speech-to-text hints built from the robot's tools (robovoice.voice.vocabulary)."""

from __future__ import annotations

from robovoice.llm.base import ToolSpec
from robovoice.voice.confidence_eval import sim_hint
from robovoice.voice.vocabulary import (
    MAX_HINT_CHARS,
    STOP_HINT,
    command_hint,
    restore,
    restore_end,
    restore_hesitation,
    restore_ring,
    restore_then_after_call,
    restore_then_call,
    restore_titles,
)

NAVIGATE = ToolSpec("navigate_to", "Drive somewhere.", {
    "type": "object",
    "properties": {"target": {"type": "string", "examples": ["kitchen", "front door"]}},
})
CALL = ToolSpec("start_video_call", "Call someone.", {
    "type": "object",
    "properties": {
        "contact": {"anyOf": [{"enum": ["Anna", "Dr. Weber"]}, {"type": "string"}]},
        "options": {"type": "object", "properties": {"camera": {"const": "front camera"}}},
        "tags": {"type": "array", "items": {"enum": ["urgent", 3]}},
    },
})
STOP = ToolSpec("stop_robot", "Stop.")


def test_hint_names_the_wake_phrase_the_tools_and_their_values() -> None:
    hint = command_hint("hey jarvis", [NAVIGATE, CALL, STOP], extra=["Grandpa Joe"])
    assert hint.startswith("Hey Jarvis. ")
    assert "navigate to, start video call, stop robot." in hint
    # examples, enum (also inside anyOf / items) and const values; non-strings are skipped
    for word in ("kitchen", "front door", "Anna", "Dr. Weber", "front camera", "urgent", "Grandpa Joe"):
        assert word in hint, word
    assert " 3" not in hint
    assert hint.endswith(STOP_HINT)


def test_repeated_words_appear_once_and_spacing_is_normalised() -> None:
    hint = command_hint("hey jarvis", [NAVIGATE, NAVIGATE], extra=["  Kitchen ", "kitchen", "living   room"])
    assert hint.count("navigate to") == 1
    assert hint.lower().count("kitchen") == 1
    assert "living room" in hint


def test_without_tools_the_hint_is_the_wake_phrase_and_the_stop_words() -> None:
    assert command_hint("hey jarvis", []) == f"Hey Jarvis. {STOP_HINT}"
    assert command_hint("", []) == STOP_HINT


def test_a_long_catalog_is_cut_but_keeps_the_wake_phrase_and_stop_words() -> None:
    many = [ToolSpec(f"tool_number_{i}", "x", {"type": "object", "properties": {
        "p": {"enum": [f"value {i}"]}}}) for i in range(100)]
    hint = command_hint("hey jarvis", many)
    assert len(hint) <= MAX_HINT_CHARS
    assert hint.startswith("Hey Jarvis. tool number 0, tool number 1")
    assert hint.endswith(STOP_HINT)
    assert ",." not in hint and ", ." not in hint


def test_doctor_misheard_before_a_known_surname_is_the_title_again() -> None:
    """Audio tests v4 and v6: Whisper wrote "Doctor Weber" as "dock to Weber", and the robot
    drove to its dock. The sim's hint names Dr. Weber, so the title is put back."""
    hint = sim_hint()
    assert "Dr. Weber" in hint
    assert restore_titles("Please call, dock to Weber.", hint) == "Please call, Dr. Weber."
    assert restore_titles("get Doc Two Weber on a video call", hint) == "get Dr. Weber on a video call"
    # only before a surname the robot knows, and only that mishearing
    assert restore_titles("go to the dock to Webster", hint) == "go to the dock to Webster"
    assert restore_titles("go back to the dock to charge", hint) == "go back to the dock to charge"
    assert restore_titles("call dock to Weber", command_hint("hey jarvis", [NAVIGATE])) == "call dock to Weber"


def test_and_the_call_alone_is_end_the_call_again() -> None:
    """CI (27 Nov 2026): "Hey Jarvis, end the call." over the remote's voice was heard as
    "And the call.", which reads as talk, and the call went on. The sim's hint names the
    end video call action, so a whole "and the (video) call" is restored."""
    hint = sim_hint()
    assert restore_end("And the call.", hint) == "End the call."
    assert restore_end("and the video call, please.", hint) == "End the video call, please."
    assert restore_end("And call!", hint) == "End call!"
    # more than the subject words, or no end_* action the robot has: as heard
    assert restore_end("And the call, was it long?", hint) == "And the call, was it long?"
    assert restore_end("and the kitchen.", hint) == "and the kitchen."
    assert restore_end("Go to the kitchen and the call.", hint) == "Go to the kitchen and the call."
    assert restore_end("And the call.", command_hint("hey jarvis", [NAVIGATE, CALL])) == "And the call."
    # … or with the next step asked after it (audio test v53), not a story that goes on
    assert restore_end("and the call and then head back to your dock.", hint) == (
        "End the call and then head back to your dock.")
    assert restore_end("and the call and then he rang off.", hint) == "and the call and then he rang off."


def test_bring_before_a_name_the_robot_can_call_is_ring_again() -> None:
    """Dev clips audio-dev-ring: Whisper tiny.en wrote "ring Clara" as "bring Clara" in 12 of 32,
    and "bring Anna" read as a drive to "Anna". The sim's hint names a call action and its
    contacts, so "bring <contact>" at a clause's start and end is "ring <contact>"."""
    hint = sim_hint()
    assert restore_ring("Bring Clara.", hint) == "Ring Clara."
    assert restore_ring("Please bring Anna.", hint) == "Please ring Anna."
    assert restore_ring("bring Ben now, please.", hint) == "ring Ben now, please."
    assert restore_ring("bring Clara, then go to the kitchen.", hint) == "ring Clara, then go to the kitchen."
    assert restore_ring("go to the bedroom, and bring Ben.", hint) == "go to the bedroom, and ring Ben."
    assert restore("bring dock for Weber.", hint) == "ring Dr. Weber."
    # something to carry after the name, a third person bringing, a name it cannot call, no call action
    assert restore_ring("Bring Ben his tea.", hint) == "Bring Ben his tea."
    assert restore_ring("Clara will bring Ben.", hint) == "Clara will bring Ben."
    assert restore_ring("bring Fred.", hint) == "bring Fred."
    assert restore_ring("Bring Kitchen.", hint) == "Bring Kitchen."
    assert restore_ring("bring Anna.", command_hint("hey jarvis", [NAVIGATE])) == "bring Anna."


def test_end_call_before_a_name_after_another_request_is_then_call_again() -> None:
    """Audio tests v34 and v37: "projector on, then call Ben" heard as "projector on, end call,
    Ben." — the call was never made. After another request, before a name the robot can call."""
    hint = sim_hint()
    assert restore_then_call("projector on, end call, Ben.", hint) == "projector on, then call Ben."
    assert restore_then_call("projector on, and end call, Ben, please.", hint) == (
        "projector on, and then call Ben, please.")
    assert restore("go to the kitchen, end call, Dr. Weber.", hint) == "go to the kitchen, then call Dr. Weber."
    # after a bare "and" (audio test v118: "go to the living room and end call Anna.")
    assert restore("go to the bedroom and end call Clara.", hint) == "go to the bedroom and then call Clara."
    # the end of a call said whole, a name it cannot call, no call action
    assert restore_then_call("End call, please.", hint) == "End call, please."
    assert restore_then_call("projector on, end the call with Ben.", hint) == "projector on, end the call with Ben."
    assert restore_then_call("projector on, end call, Fred.", hint) == "projector on, end call, Fred."
    assert restore_then_call("projector on, end call, Ben.", command_hint("hey jarvis", [NAVIGATE])) == (
        "projector on, end call, Ben.")


def test_ben_between_a_call_and_a_verb_is_then() -> None:
    """Audio test v39: "call Anna, then head to the hallway" heard as "call Anna, Ben, head to
    the hallway, …": the call read as corrected to Ben, the drive never made."""
    hint = sim_hint()
    assert restore_then_after_call("call Anna, Ben, head to the hallway.", hint) == (
        "call Anna, then head to the hallway.")
    assert restore("ring Dr. Weber, Ben, switch the projector on.", hint) == (
        "ring Dr. Weber, then switch the projector on.")
    assert restore("kindly finish this call, and Ben Ring, Dr. Weber, it is time.", hint) == (
        "kindly finish this call, and then ring Dr. Weber, it is time.")  # audio test v40
    assert restore_then_after_call("switch it off. And Ben, ring Clara.", hint) == "switch it off. And Ben, ring Clara."
    assert restore("bring our Anna, then put the projector on.", hint) == "ring our Anna, then put the projector on."
    # a list of names, Ben called himself, no verb after, no call action
    assert restore_then_after_call("call Anna, Ben and Clara.", hint) == "call Anna, Ben and Clara."
    assert restore_then_after_call("call Ben, Ben, go.", hint) == "call Ben, Ben, go."
    assert restore_then_after_call("call Anna, Ben, please.", hint) == "call Anna, Ben, please."
    assert restore_then_after_call("call Anna, Ben, head off.", command_hint("hey jarvis", [NAVIGATE])) == (
        "call Anna, Ben, head off.")


def test_an_opening_or_before_a_verb_is_a_hesitation() -> None:
    """Audio test v44: "er, go to the kitchen, would you" heard as "or go to the kitchen, would
    you?" read as talk."""
    assert restore_hesitation("or go to the kitchen, would you?") == "go to the kitchen, would you?"
    assert restore_hesitation("Or, ring Ben.") == "ring Ben."
    for kept in ("Or so they say.", "Oregon is nice.", "or the bedroom", "Go there, or ring Ben."):
        assert restore_hesitation(kept) == kept
    assert restore("or go to the kitchen.", "") == "go to the kitchen."
