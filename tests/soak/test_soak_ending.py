"""A soak asked to end early (`run_soak(ending=...)`, what `robovoice bench soak` does on SIGINT
or SIGTERM) stops after the command under way and still reports, marked as ended early: a
2-hour run can be read before its end."""

from __future__ import annotations

import asyncio

import pytest

from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.soak import SoakSettings, run_soak
from robovoice.soak.cli import summary

from ..voice.voice_kit import fake_models

pytestmark = [pytest.mark.timeout(300)]


async def test_a_soak_asked_to_end_reports_what_it_has(backend: OpenAICompatBackend) -> None:
    ending = asyncio.Event()
    settings = SoakSettings(hours=2.0, seed=2, mean_gap_minutes=0.5, sample_minutes=0.5, warm_up_minutes=0.5)
    loop = asyncio.get_running_loop()
    loop.call_later(3.0, ending.set)  # as the signal handler does, a few seconds in
    async with asyncio.timeout(240):
        report = await run_soak(fake_models(), backend, settings, ending=ending)
    assert report.settings["ended_early"] is True
    # a drive the fake models never start is not waited on for a minute once the end is asked
    assert report.wall_s < 30.0, report.wall_s
    assert 0 < report.sim_hours < 2.0
    assert len(report.samples) >= 2  # the first sample and the one taken at the end
    assert report.errors["unhandled"] == [], report.errors
    assert report.leaks["tasks_left"] <= 0, report.leaks
    assert "ended early: a partial run" in summary(report)
