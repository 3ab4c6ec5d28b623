"""The soak's spoken stop during a drive. The first 2-hour soak lost 3/3 of them: its sim ran
at 10x, so a drive ended (1-2.4 s wall) before the stop line had been said and transcribed
(a test here); and heard through the room while the robot said "On my way to the front door.",
Whisper tiny.en made "Stop my robot!" of the stop line, which the stop grammar refused
(tests/voice/test_stop_words.py). Here also: the clean stop line is heard as a stop; the whole
scenario (the stop clip said 0.5 s into a drive reaches the robot before it arrives, with no
action nobody asked for); a robot whose battery is low is sent to its charging dock."""

from __future__ import annotations

import numpy as np
import pytest

from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.sim import SimState
from robovoice.sim.body import DEFAULT_MAX_SPEED_MPS, Pose
from robovoice.sim.world import PLACES, route, route_length
from robovoice.soak import SoakSettings, run_soak
from robovoice.soak.cli import summary
from robovoice.soak.script import DOCK, STOP_LINE, STOP_PLACES, Command, next_command
from robovoice.soak.sounds import SoakSounds
from robovoice.voice.models import VoiceModels
from robovoice.voice.stop import is_stop_command
from robovoice.voice.vocabulary import STOP_HINT

pytestmark = [pytest.mark.integration, pytest.mark.timeout(600)]


def test_the_soaks_stop_line_as_whisper_hears_it_is_a_stop(voice_models: VoiceModels) -> None:
    assert voice_models.stt is not None
    clip = SoakSounds(voice_models.tts, np.random.default_rng(1)).command(STOP_LINE)
    text = voice_models.stt.transcribe(clip, STOP_HINT).text
    assert is_stop_command(text), text


def test_the_soaks_stop_drives_last_long_enough_to_be_stopped() -> None:
    # the stop line is said 0.5 s after the robot starts moving; it lasts ~1.2 s, then the end of
    # speech (~0.5 s) and a transcription (1-2 s on a quiet machine, 15 s seen at load 20) come
    speed = SoakSettings().sim_speed
    shortest = min(route_length(route(a.position, b.position)) / DEFAULT_MAX_SPEED_MPS / speed
                   for a in PLACES for b in PLACES if b.name in STOP_PLACES and b is not a and a.blocked is None)
    assert shortest >= 8.0, f"a stop drive may last only {shortest:.1f} s wall at sim speed {speed:g}"


async def test_the_soaks_spoken_stop_reaches_the_robot_during_a_drive(voice_models: VoiceModels,
                                                                       backend: OpenAICompatBackend) -> None:
    # from the dock to the front door (8.3 m). The sim runs at 1/4 speed here (the drive takes 66 s
    # wall, not 17): on this shared 2-core machine at load 20 one transcription took 28 s, and
    # what is tested is that the stop is heard as one and reaches the robot mid-drive
    stop = Command("stop", "Hey Jarvis, go to the front door.", "navigate_to", follow=STOP_LINE)
    settings = SoakSettings(hours=3 / 60, seed=5, mean_gap_minutes=0.3, sample_minutes=1.0, warm_up_minutes=0.5,
                            sim_speed=0.25)
    report = await run_soak(voice_models, backend, settings, commands=[stop])
    commands = report.commands
    assert commands["by_kind"]["stop"] == {"given": 1, "answered": 1, "done": 1}, summary(report)
    assert report.unasked_actions["count"] == 0, report.unasked_actions
    assert report.errors["unhandled"] == [], report.errors


def _state(battery_percent: float, nearest_place: str = "kitchen") -> SimState:
    return SimState(pose=Pose(0.0, 0.0, 0.0), nearest_place=nearest_place, moving=False, driving_target=None,
                    projector_on=False, call_contact=None, remote_speaking=False,
                    battery_percent=battery_percent, charging=nearest_place == DOCK, max_speed_mps=0.5,
                    collision_avoidance=True)


def test_a_low_battery_sends_the_robot_to_its_dock_first() -> None:
    rng = np.random.default_rng(0)
    low = [next_command(rng, _state(battery_percent=12.0)) for _ in range(5)]
    assert {(c.kind, c.place, c.say) for c in low} == {("drive", DOCK, f"Hey Jarvis, go to the {DOCK}.")}
    # at the dock (charging) or with enough battery, the random script goes on
    docked = {next_command(rng, _state(battery_percent=12.0, nearest_place=DOCK)).place for _ in range(40)}
    assert docked != {DOCK}
