"""WakeDecider and WakeWordSpotter with made-up scores (no models)."""

from __future__ import annotations

import numpy as np
import pytest

from robovoice.audio.fakes import ScriptedWakeDetector
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, AudioFormat
from robovoice.audio.wake import (
    WakeDecider,
    WakeDeciderConfig,
    WakeDetected,
    WakeWordDetector,
    WakeWordSpotter,
)
from robovoice.errors import AudioError, ConfigError

FRAME = 0.08


def run(decider: WakeDecider, scores: list[float], t0: float = 0.0) -> list[WakeDetected]:
    events = []
    for i, s in enumerate(scores):
        e = decider.update(s, t0 + (i + 1) * FRAME)
        if e is not None:
            events.append(e)
    return events


def test_fires_on_the_first_frame_over_threshold_with_its_time() -> None:
    events = run(WakeDecider(), [0.0, 0.1, 0.3, 0.7, 0.95, 0.9, 0.2, 0.0])
    assert len(events) == 1
    assert events[0].score == 0.7
    assert events[0].timestamp == pytest.approx(4 * FRAME)


def test_one_utterance_wakes_once_even_with_a_dip_inside() -> None:
    # the score dips below threshold but not below threshold * rearm_ratio, then rises again
    events = run(WakeDecider(), [0.9, 0.95, 0.4, 0.8, 0.99, 0.6, 0.0])
    assert len(events) == 1


def test_refractory_period_blocks_a_second_detection_shortly_after() -> None:
    cfg = WakeDeciderConfig(threshold=0.5, refractory_s=2.0)
    scores = [0.9, 0.0, 0.0, 0.9] + [0.0] * 30 + [0.9]  # second peak 0.24 s after, third 2.8 s after
    events = run(WakeDecider(cfg), scores)
    assert [round(e.timestamp, 2) for e in events] == [0.08, 2.8]


def test_requires_consecutive_frames_when_asked() -> None:
    cfg = WakeDeciderConfig(threshold=0.5, min_frames=3)
    assert run(WakeDecider(cfg), [0.9, 0.9, 0.1, 0.9, 0.9, 0.1]) == []
    events = run(WakeDecider(cfg), [0.9, 0.6, 0.99, 0.7])
    assert len(events) == 1
    assert events[0].timestamp == pytest.approx(3 * FRAME)
    assert events[0].score == pytest.approx(0.99)  # peak of the run


def test_threshold_can_be_raised_while_the_robot_speaks_and_restored() -> None:
    d = WakeDecider()
    d.set_threshold(0.9)
    assert d.threshold == 0.9
    assert run(d, [0.7, 0.8, 0.0]) == []
    assert len(run(d, [0.95], t0=10.0)) == 1
    d.set_threshold(None)
    assert d.threshold == WakeDeciderConfig().threshold
    with pytest.raises(ConfigError):
        d.set_threshold(1.5)


def test_reset_forgets_refractory_state() -> None:
    d = WakeDecider(WakeDeciderConfig(refractory_s=10.0))
    assert len(run(d, [0.9])) == 1
    assert run(d, [0.0, 0.9]) == []
    d.reset()
    assert len(run(d, [0.9])) == 1


@pytest.mark.parametrize(
    "kwargs",
    [{"threshold": 0.0}, {"threshold": 1.2}, {"min_frames": 0}, {"refractory_s": -1.0}, {"rearm_ratio": 2.0}],
)
def test_bad_config_is_refused(kwargs: dict[str, float]) -> None:
    with pytest.raises(ConfigError):
        WakeDeciderConfig(**kwargs)  # type: ignore[arg-type]  # one bad option at a time, by name


def test_spotter_frames_audio_and_stamps_events_with_frame_end() -> None:
    detector = ScriptedWakeDetector([0.0, 0.0, 0.0, 0.8, 0.9, 0.1])
    assert isinstance(detector, WakeWordDetector)
    spotter = WakeWordSpotter(detector)
    audio = np.zeros(1280 * 6 + 100, dtype=np.int16)
    events = []
    for i in range(0, len(audio), 1000):  # chunks that do not align with frames
        events += spotter.feed(AudioChunk(audio[i : i + 1000], MODEL_FORMAT, 3.0 + i / 16000))
    assert detector.frames_seen == 6
    assert [type(e) for e in events] == [WakeDetected]
    assert events[0].score == 0.8
    assert events[0].timestamp == pytest.approx(3.0 + 4 * FRAME)
    assert spotter.last_score == pytest.approx(0.1)
    spotter.reset()
    assert detector.resets == 1


def test_spotter_refuses_audio_that_is_not_16k_mono() -> None:
    spotter = WakeWordSpotter(ScriptedWakeDetector())
    with pytest.raises(AudioError, match="16 kHz mono"):
        spotter.feed(AudioChunk(np.zeros(100, np.int16), AudioFormat(48000)))


# --- unsure detections (a score under the threshold, checked later against the transcript) ---


def unsure(threshold: float = 0.6, floor: float = 0.1) -> WakeDecider:
    return WakeDecider(WakeDeciderConfig(threshold=threshold, unsure_threshold=floor))


def test_a_run_under_the_threshold_is_reported_unsure_when_it_ends_with_its_first_frames_time() -> None:
    events = run(unsure(), [0.0, 0.05, 0.2, 0.43, 0.3, 0.05, 0.0])
    assert len(events) == 1
    assert not events[0].sure
    assert events[0].score == pytest.approx(0.43)  # the run's peak
    assert events[0].timestamp == pytest.approx(3 * FRAME)  # its first frame over the floor


def test_a_run_that_reaches_the_threshold_is_one_sure_detection() -> None:
    events = run(unsure(), [0.2, 0.4, 0.9, 0.5, 0.2, 0.05, 0.0])
    assert [(e.sure, e.score) for e in events] == [(True, 0.9)]  # the rising edge and tail are not reported


def test_no_unsure_detections_without_a_floor_or_while_the_threshold_is_raised() -> None:
    assert run(WakeDecider(), [0.2, 0.5, 0.3, 0.0]) == []
    d = unsure()
    d.set_threshold(0.7)  # the robot is speaking
    assert run(d, [0.2, 0.5, 0.3, 0.0]) == []
    d.set_threshold(None)
    assert [e.sure for e in run(d, [0.2, 0.5, 0.3, 0.0], t0=5.0)] == [False]


def test_the_floor_must_be_under_the_threshold() -> None:
    with pytest.raises(ConfigError, match="under the wake threshold"):
        WakeDeciderConfig(threshold=0.6, unsure_threshold=0.6)


def test_the_spotter_holds_off_the_other_offsets_only_for_a_sure_detection() -> None:
    class Holding(ScriptedWakeDetector):
        held = 0

        def hold_off(self, seconds: float) -> None:
            self.held += 1

    detector = Holding([0.3, 0.0, 0.0, 0.9, 0.0])
    spotter = WakeWordSpotter(detector, unsure())
    events = spotter.feed(AudioChunk(np.zeros(1280 * 5, dtype=np.int16), MODEL_FORMAT, 0.0))
    assert [e.sure for e in events] == [False, True]
    assert detector.held == 1
