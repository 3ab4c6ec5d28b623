"""The spoken stop's grammar (`stop.is_stop_command`) on what speech-to-text makes of real stop
lines: Whisper tiny.en hears the soak's Piper "Stop the robot!" as "Stop my robot!", which the
first soak's three stops were lost to."""

from __future__ import annotations

import pytest

from robovoice.voice.stop import is_stop_command, says_stop


@pytest.mark.parametrize("text", ["Stop my robot!", "stop my robot", "Stop my robot now!", "Please stop my robot."])
def test_what_whisper_hears_for_stop_the_robot_is_a_stop(text: str) -> None:
    assert is_stop_command(text)


@pytest.mark.parametrize("text", ["Stop one robot!", "Stop when robot!", "Stop one of the robot!",
                                  "Stop that robot!", "Hold it right there!", "Hold it!",
                                  "Stop writing there. Please!", "Stop riding there!"])
def test_a_misheard_determiner_or_hold_it_is_a_stop(text: str) -> None:
    # how Whisper heard Piper's "Stop the robot!" with the robot's "One moment." over it
    assert is_stop_command(text)


@pytest.mark.parametrize("text", ["Stop my call.", "Stop my music.", "Don't stop my robot.",
                                  "Stop my robot at the kitchen.", "Stop the kitchen robot.",
                                  "Stop the robot's music.", "Stop the video there."])
def test_stop_my_something_else_is_not_a_stop(text: str) -> None:
    assert not is_stop_command(text)


@pytest.mark.parametrize("text", ["Please stop the robot.", "Stop the robot now!", "Stop the robot, please.",
                                  "Okay, stop the robot right now.", "Whoa whoa stop!", "Woah, hold it right there!"])
def test_a_stop_phrase_with_fillers_around_it_is_a_stop(text: str) -> None:
    # "robot" is a filler too: stripping it first used to leave "stop the", which is no stop
    assert is_stop_command(text)


@pytest.mark.parametrize("text", ["Wait, wait, stay there!", "Hold on, stay put.", "Okay, wait! Don't move!",
                                  "Stay right there, please.", "Stop, stop, wait there.",
                                  "Whoa, whoa, hold your horses!", "Hang on, stand still.",
                                  "Hold still!", "Keep still, please."])
def test_several_stop_phrases_in_a_row_are_a_stop(text: str) -> None:
    # the words people use for "stop" beside "stop", one after another with or without commas
    assert is_stop_command(text)


@pytest.mark.parametrize("text", ["Wait for me in the kitchen.", "Stay in the bedroom.", "Hold on to the call.",
                                  "Wait, go to the kitchen.", "Don't move the projector.", "Stay there till I come.",
                                  "Hang on to the call.", "Stand still in the hallway."])
def test_a_stop_word_with_a_request_is_not_a_stop(text: str) -> None:
    assert not is_stop_command(text)


@pytest.mark.parametrize("text", ["Stop, man!", "No, no, stop!", "Oi! Stop there.", "Right, stop. Please."])
def test_while_moving_a_stop_clause_of_its_own_is_a_stop(text: str) -> None:
    assert says_stop(text) and not is_stop_command(text)


@pytest.mark.parametrize("text", ["Hold!", "Hold, hold, the cat!"])
def test_while_moving_hold_said_alone_is_a_stop(text: str) -> None:
    assert says_stop(text)  # (audio test v99: "Halt, halt, …" heard as "hold, hold, …"; "Hold on to it." is not)
    assert not says_stop("Hold the door for me.") and not says_stop("Hold on to the rail.")


@pytest.mark.parametrize("text", ["Falt!", "Stob!", "Okay, salt!"])
def test_while_moving_a_near_miss_of_stop_said_alone_is_a_stop(text: str) -> None:
    assert says_stop(text) and not is_stop_command(text)


@pytest.mark.parametrize("text", ["What?", "Top!", "Falt the car.", "Go!", "Stood."])
def test_while_moving_a_word_not_close_to_stop_or_a_near_miss_with_more_is_not(text: str) -> None:
    assert not says_stop(text)


@pytest.mark.parametrize("text", ["Don't stop, keep going.", "Stop? No, carry on.", "I told him to stop the car.",
                                  "Go to the kitchen.", "Stop the call, please.", "Hold it up to the light.", ""])
def test_while_moving_carrying_on_or_other_words_are_not_a_stop(text: str) -> None:
    assert not says_stop(text)
