"""The listener's wake word decisions around the end of playback: a detection reports a phrase
said up to `WAKE_WINDOW_S` before it, so playback that stopped before the detector fired (a
sentence ending in "Hey Jarvis", the next one not yet synthesised) still counts."""

from __future__ import annotations

import numpy as np

from robovoice.audio.fakes import EnergyVAD, ScriptedWakeDetector, ToneWakeDetector
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, concat
from robovoice.audio.vad import Endpointer, SpeechSegmenter
from robovoice.audio.wake import WakeDecider, WakeWordSpotter
from robovoice.voice.config import PipelineConfig
from robovoice.voice.echo import PlaybackReference
from robovoice.voice.listener import FRAME_SAMPLES, PLAYBACK_MATCH_WAIT_S, WAKE_WINDOW_S, HeardWake, Listener

from .voice_kit import WAKE_TONE_HZ, tone

FRAME_S = FRAME_SAMPLES / MODEL_FORMAT.rate
PLAYBACK = (1.0, 1.5)  # the robot's sentence sounds from 1.0 s to 1.5 s
TAIL_S = 0.3


def listen(playback: AudioChunk, fires_at: float, until: float = 3.2,
           score: float = 0.99) -> tuple[list[HeardWake], dict[float, float]]:
    """A silent room where the microphone's wake detector fires on the frame ending at
    `fires_at` (a detector's latency after the phrase) while `playback` played over `PLAYBACK`;
    the wakes heard, and the wake threshold in force after each frame (by its end time)."""
    cfg = PipelineConfig.from_config()
    reference = PlaybackReference()
    reference.place(playback, PLAYBACK[0])
    fire_frame = round(fires_at / FRAME_S) - 1
    mic_detector = ScriptedWakeDetector([0.0] * fire_frame + [score])
    listener = Listener(WakeWordSpotter(mic_detector, WakeDecider(cfg.wake)),
                        SpeechSegmenter(EnergyVAD(), Endpointer(cfg.endpointer)), reference, cfg.echo,
                        playback_detector=ToneWakeDetector(), playback_tail_s=TAIL_S)
    wakes: list[HeardWake] = []
    thresholds: dict[float, float] = {}
    for k in range(round(until / FRAME_S)):
        heard = listener.process(AudioChunk(np.zeros(FRAME_SAMPLES, dtype=np.int16), MODEL_FORMAT, k * FRAME_S))
        wakes += [e for e in heard.events if isinstance(e, HeardWake)]
        thresholds[round(heard.now, 2)] = listener.spotter.decider.threshold
    return wakes, thresholds


def test_the_robots_own_wake_phrase_detected_after_its_playback_ended_is_rejected() -> None:
    # the playback ends at 1.5 s; the detector fires 0.74 s later, after the 0.3 s echo tail
    said_by_robot = tone(PLAYBACK[1] - PLAYBACK[0], hz=WAKE_TONE_HZ)
    (wake,), _ = listen(said_by_robot, fires_at=2.24)
    assert wake.at > PLAYBACK[1] + TAIL_S
    assert wake.during_playback and not wake.near_end, "the robot's own 'Hey Jarvis' must not wake it"
    assert wake.playback_score > 0.5


def test_a_person_right_after_the_robot_is_heard_and_playback_long_ago_does_not_count() -> None:
    talk = tone(PLAYBACK[1] - PLAYBACK[0], hz=440.0)  # the robot said something, not the wake phrase
    (wake,), _ = listen(talk, fires_at=2.24)
    assert wake.during_playback and wake.near_end, "the person's wake word counts"
    later = PLAYBACK[1] + TAIL_S + WAKE_WINDOW_S + 0.5
    (quiet,), _ = listen(tone(0.5, hz=WAKE_TONE_HZ), fires_at=round(later / FRAME_S) * FRAME_S, until=later + 0.5)
    assert not quiet.during_playback and quiet.near_end and quiet.playback_score == 0.0


def test_the_raised_threshold_covers_the_audio_the_detector_scores() -> None:
    cfg = PipelineConfig.from_config()
    _, thresholds = listen(tone(0.5, hz=440.0), fires_at=3.04)
    raised, normal = cfg.echo.playback_wake_threshold, cfg.wake.threshold
    assert raised > normal
    assert thresholds[0.96] == normal  # nothing played yet
    assert thresholds[1.2] == raised and thresholds[2.4] == raised  # up to the window after the tail
    assert thresholds[3.12] == normal


def test_a_wake_heard_a_frame_before_the_playback_says_it_waits_for_the_playbacks_score() -> None:
    # the playback talks for 0.24 s, then says the wake phrase; the microphone's detector fires
    # on the frame before the playback's own detector scores it (either may cross first: a
    # remote caller's "Hey Jarvis" in the demo)
    said_by_remote = concat([tone(0.24, hz=440.0), tone(0.26, hz=WAKE_TONE_HZ)])
    (wake,), _ = listen(said_by_remote, fires_at=PLAYBACK[0] + 0.28)
    assert wake.during_playback and not wake.near_end, "the playback said it a frame later: its own voice"
    assert wake.playback_score > 0.5
    talk = tone(0.5, hz=440.0)
    (person,), _ = listen(talk, fires_at=PLAYBACK[0] + 0.28)
    assert person.during_playback and person.near_end and person.at == wake.at
    assert PLAYBACK_MATCH_WAIT_S <= 2 * FRAME_S  # a person's barge-in waits at most two frames


def test_an_unsure_score_counts_only_away_from_playback() -> None:
    talk = tone(PLAYBACK[1] - PLAYBACK[0], hz=440.0)
    assert listen(talk, fires_at=1.6, score=0.4)[0] == []  # the robot was speaking: no unsure wake
    later = PLAYBACK[1] + TAIL_S + WAKE_WINDOW_S + 0.5
    (wake,), _ = listen(talk, fires_at=round(later / FRAME_S) * FRAME_S, until=later + 0.5, score=0.4)
    assert not wake.sure and not wake.during_playback and wake.near_end
