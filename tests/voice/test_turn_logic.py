"""Pure decision logic of the voice pipeline: turn-taking, the stop phrases, spoken progress,
the wake phrase in transcripts, the robot's own words."""

from __future__ import annotations

import pytest

from robovoice.config import VoiceConfig
from robovoice.voice.config import SpeechConfig, TurnTakingConfig
from robovoice.voice.progress import ProgressNarrator
from robovoice.voice.stop import is_stop_command
from robovoice.voice.turns import Action, Phase, TurnTaking
from robovoice.voice.utterance import OwnWords, addressed_elsewhere, names_robot, strip_wake_words

from .voice_kit import sim_voice_roles

# --- turn-taking ----------------------------------------------------------------------------------


def _turns(**settings: float) -> TurnTakingConfig:
    return TurnTakingConfig.from_config(VoiceConfig.model_validate(settings))


def test_listening_ignores_speech_without_the_wake_word() -> None:
    t = TurnTaking(_turns())
    assert t.phase(0.0) is Phase.LISTENING
    verdict = t.classify(1.0, 2.5, moving=False)
    assert verdict.action is Action.IGNORE and verdict.reason == "no_wake_word"


def test_wake_word_inside_the_utterance_makes_it_a_command_once() -> None:
    t = TurnTaking(_turns())
    t.wake(1.2)
    assert t.phase(1.3) is Phase.WOKEN
    assert t.addressed(0.8, 3.0)
    verdict = t.classify(0.8, 3.0, moving=False)
    assert verdict.action is Action.COMMAND and verdict.wake_at == 1.2
    assert t.classify(4.0, 5.0, moving=False).action is Action.IGNORE, "a wake word is used once"


def test_wake_word_then_pause_then_command_within_the_timeout() -> None:
    t = TurnTaking(_turns(command_timeout_s=6.0))
    t.wake(1.0)
    t.rearm(1.3)  # the first utterance was the wake phrase alone
    rearmed = t.classify(3.0, 4.5, moving=False)
    assert rearmed.action is Action.COMMAND and rearmed.rearmed  # no wake word was said for it
    t.wake(8.0)
    heard = t.classify(8.2, 9.0, moving=False)
    assert heard.wake_at == 8.0 and not heard.rearmed
    t.wake(10.0)
    assert t.expire(17.0)
    assert t.phase(17.0) is Phase.LISTENING
    assert t.classify(18.0, 19.0, moving=False).action is Action.IGNORE


def test_a_long_command_begun_within_the_timeout_keeps_its_wake_word() -> None:
    t = TurnTaking(_turns(command_timeout_s=6.0))
    t.wake(1.4)
    assert not t.expire(7.5, speaking_since=0.3)  # "Hey Jarvis, …" still being said at 7.5 s
    assert t.classify(0.3, 7.0, moving=False).action is Action.COMMAND
    t.wake(10.0)
    assert t.expire(17.0, speaking_since=16.5), "speech begun after the timeout is not the command"


def test_short_speech_while_moving_is_checked_for_a_stop() -> None:
    t = TurnTaking(_turns(stop_max_s=2.5))
    assert t.classify(1.0, 1.6, moving=True).action is Action.STOP_CHECK
    assert t.classify(1.0, 5.0, moving=True).action is Action.IGNORE, "long talk is not a stop"


def test_phases_through_a_turn_and_the_follow_up_window() -> None:
    t = TurnTaking(_turns(follow_up_s=5.0, playback_tail_s=0.3))
    t.wake(1.0)
    t.classify(0.5, 2.0, moving=False)
    t.turn_started()
    assert t.phase(2.5) is Phase.IN_TURN and t.busy
    t.playback(True, 3.0)
    assert t.phase(3.0) is Phase.SPEAKING
    t.turn_finished(asked_question=True)
    t.playback(False, 6.0)
    assert t.phase(6.5) is Phase.FOLLOW_UP and not t.busy
    assert t.classify(6.1, 6.8, moving=False).action is Action.IGNORE, "inside the echo tail: not an answer"
    t2 = TurnTaking(_turns(follow_up_s=5.0, playback_tail_s=0.3))
    t2.turn_started()
    t2.playback(True, 3.0)
    t2.turn_finished(asked_question=True)
    t2.playback(False, 6.0)
    verdict = t2.classify(7.0, 8.0, moving=False)
    assert verdict.action is Action.COMMAND and verdict.follow_up
    assert t2.phase(12.0) is Phase.LISTENING


def test_no_follow_up_after_a_statement() -> None:
    t = TurnTaking(_turns())
    t.turn_started()
    t.playback(True, 1.0)
    t.turn_finished(asked_question=False)
    t.playback(False, 3.0)
    assert t.phase(3.5) is Phase.LISTENING
    assert t.classify(4.0, 5.0, moving=False).action is Action.IGNORE


def test_a_cancelled_turn_opens_no_follow_up() -> None:
    t = TurnTaking(_turns())
    t.turn_started()
    t.playback(True, 1.0)
    t.turn_cancelled()
    t.playback(False, 1.5)
    assert t.phase(2.0) is Phase.LISTENING


# --- stop phrases ------------------------------------------------------------------------------------


@pytest.mark.parametrize("text", [
    "Stop", "Stop!", "stop.", "Stop the robot!", "Halt!", "Stop, stop!", "Please stop.", "Stop now.",
    "Hey Jarvis, stop!", "Jarvis, halt.", "Okay robot, stop right now!", "STOP STOP STOP", "Freeze!",
    "Stop moving.", "Emergency stop!",
])  # fmt: skip
def test_stop_phrases(text: str) -> None:
    assert is_stop_command(text)


@pytest.mark.parametrize("text", [
    "", "Don't stop.", "Stop the call.", "Stop at the kitchen.", "Start.", "Go to the bus stop.",
    "I will stop by later.", "Stopwatch", "Hey Jarvis.", "Halte", "Please go to the kitchen and stop there",
])  # fmt: skip
def test_not_stop_phrases(text: str) -> None:
    assert not is_stop_command(text)


# --- progress ------------------------------------------------------------------------------------------


def test_long_actions_are_acknowledged_then_reported_at_most_every_interval() -> None:
    n = ProgressNarrator(SpeechConfig.from_config(VoiceConfig(progress_interval_s=8.0)), sim_voice_roles())
    assert n.on_call("set_projector_power", {"on": True}, 0.0) is None
    assert n.on_call("navigate_to", {"target": "kitchen"}, 0.0) == "On my way to the kitchen."
    assert n.on_progress("navigate_to", 1.0, 8.0, "7 m to the kitchen", 2.0) is None, "throttled"
    assert n.on_progress("navigate_to", 4.0, 8.0, "4 m to the kitchen", 8.5) == (
        "Still on my way, 4 metres to the kitchen.")
    assert n.on_progress("navigate_to", 5.0, 8.0, "3 m to the kitchen", 10.0) is None
    assert n.on_progress("navigate_to", 8.0, 8.0, "arrived at the kitchen", 30.0) is None, "the model says the result"
    assert n.on_call("return_to_dock", {}, 40.0) == "Going back to my charging dock."
    assert n.on_progress("navigate_to", 2.0, 10.0, "1.5 m to the hallway", 60.0) == (
        "Still on my way, 1.5 metres to the hallway.")


# --- transcripts -------------------------------------------------------------------------------------


@pytest.mark.parametrize(("heard", "command"), [
    ("Hey Jarvis, turn on the projector.", "turn on the projector."),
    ("Hey, Jarvis,, which places do you know?", "which places do you know?"),
    ("Hey Jervis go to the kitchen", "go to the kitchen"),
    ("Jarvis, stop!", "stop!"),
    ("Hey Jarvis.", ""),
    ("Turn on the projector.", "Turn on the projector."),
    ("hey jarvis. Go to the kitchen", "Go to the kitchen"),
    ("Turn on the Jarvis mode", "Turn on the Jarvis mode"),
    ("Breathe, hey Jarvis, call Anna.", "call Anna."),  # a television's last word before the wake phrase
    ("The home team. Hey, Jarvis, go to the kitchen.", "go to the kitchen."),
    ("Call Anna, Jarvis.", "Call Anna, Jarvis."),  # the name alone is only taken at the start
])  # fmt: skip
def test_wake_phrase_is_removed_from_the_transcript(heard: str, command: str) -> None:
    assert strip_wake_words(heard) == command


@pytest.mark.parametrize(("heard", "elsewhere"), [
    ("Hey Charlie, go along to the front door, will you?", True),  # audio test v4's near miss
    ("Hello Anna, how are you?", True),
    ("Hey Jarvis, go to the kitchen.", False),
    ("Hey Travis, go to the kitchen.", False),  # the wake name misheard: still the phrase
    ("Hey, I want the projector on.", False),
    ("Hey, could you come here?", False),
    ("Hey Robot, come here.", False),
    ("Go to the kitchen.", False),
])  # fmt: skip
def test_a_transcript_calling_someone_else_by_name_is_addressed_elsewhere(heard: str, elsewhere: bool) -> None:
    assert addressed_elsewhere(heard) is elsewhere


@pytest.mark.parametrize(("heard", "named"), [
    ("Hey Jarvis, go to the kitchen.", True),
    ("Hey, Jarvis. Turn the projector on.", True),
    ("Jarvis, stop!", True),
    ("The home team. Hey, Jarvis, go to the kitchen.", True),
    ("Hey Travis, go to the kitchen, please.", False),  # a wake score of 0.48, and somebody else's name
    ("Hey Jervis, go to the kitchen.", False),  # close is not enough for an unsure wake
    ("Go to the kitchen.", False),
    ("Right, off you go to the bedroom, and tell Jarvis.", False),  # the name after the command
])  # fmt: skip
def test_an_unsure_wake_needs_the_robots_name_spelt_out_at_the_start(heard: str, named: bool) -> None:
    assert names_robot(heard) is named


def test_an_unsure_wake_word_is_marked_and_does_not_replace_a_sure_one() -> None:
    t = TurnTaking(_turns())
    t.wake(1.0, sure=False)
    verdict = t.classify(0.8, 3.0, moving=False)
    assert verdict.action is Action.COMMAND and not verdict.wake_sure
    t.wake(5.0)
    t.wake(5.4, sure=False)  # the tail of the same phrase, or talk after it
    verdict = t.classify(4.8, 7.0, moving=False)
    assert verdict.wake_at == 5.0 and verdict.wake_sure
    t.wake(9.0, sure=False)
    t.rearm(9.5)  # the transcript named the robot and held nothing more: sure from now on
    assert t.classify(10.0, 11.0, moving=False).wake_sure


def test_own_words_are_recognised_for_a_while() -> None:
    now = [0.0]
    own = OwnWords(keep_s=15.0, clock=lambda: now[0])
    own.add("I will stop at the kitchen. Please stay where you are.")
    assert own.contains("Stop.") and own.contains("stay where you are")
    assert not own.contains("Stop the robot!")
    now[0] = 20.0
    assert not own.contains("Stop.")


def test_the_robots_own_words_misheard_as_a_stop_are_its_own_voice() -> None:
    """Audio test v52: during a drive the robot's "All right, I won't." came back through the
    microphone as "Alright, hold on." and stopped the robot. Misheard own words are its own voice
    only when the utterance was heard mostly during playback and no louder than its echo."""
    from types import SimpleNamespace

    from robovoice.voice.stopping import StopController

    now = [0.0]
    own = OwnWords(keep_s=15.0, clock=lambda: now[0])
    own.add("All right, I won't.")
    assert own.resembles("Alright, hold on.") and not own.resembles("Stop!") and not own.resembles("wait")
    checks = SimpleNamespace(own_words=own)
    assert StopController._misheard_own(checks, 0.9, False, "Alright, hold on.")  # type: ignore[arg-type]
    assert not StopController._misheard_own(checks, 0.9, True, "Alright, hold on.")  # type: ignore[arg-type]
    assert not StopController._misheard_own(checks, 0.2, False, "Alright, hold on.")  # type: ignore[arg-type]
    assert not StopController._misheard_own(checks, 0.9, False, "Stop the robot!")  # type: ignore[arg-type]
    now[0] = 20.0
    assert not own.resembles("Alright, hold on.")
