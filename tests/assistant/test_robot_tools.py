"""The robot's tools as the assistant gets them over MCP: each manifest's voice section
travels in the tool's ``_meta`` and is read back from ``tools/list``."""

from __future__ import annotations

import logging

import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.robot_tools import voice_section
from robovoice.config import RobotConfig
from robovoice.manifest.voice import META_KEY


async def test_voice_sections_reach_the_client_in_the_tools_meta() -> None:
    async with connect_robot(RobotConfig(address="sim://?speed=5")) as robot:
        listing = await robot.tools.client.list_tools()
        meta = {t.name: (t.meta or {}).get(META_KEY) for t in listing.tools}
        await robot.tools.specs()
        voice = robot.tools.voice()
    words = {name: section.pop("words") for name, section in meta.items() if section and "words" in section}
    assert set(words) == {"navigate_to", "return_to_dock", "cancel_navigation", "stop_robot",
                          "set_projector_power", "start_video_call", "end_video_call"}  # the actuation tools
    assert "ring" in words["start_video_call"] and tuple(words["start_video_call"]) == voice["start_video_call"].words
    assert meta["navigate_to"] == {"role": "motion", "say": {"start": "On my way to the {target}.",
                                                             "progress": "Still on my way, {message}.",
                                                             "success": "I am {where} now.",
                                                             "confirm": "Shall I go to the {target}?"}}
    assert meta["stop_robot"] == {"role": "stop", "say": {"success": "{was_moving:Stopped.|I am standing still.}"}}
    assert meta["get_robot_pose"] == {"role": "pose", "say": {"success": "I am near the {nearest_place}."}}
    projector = "The projector {changed:is now|was already} {on:on|off}."
    assert meta["set_projector_power"] == {"say": {"success": projector}}
    battery = "My battery is at {percent:.0f} percent{charging:, and I am charging|}."
    assert meta["get_battery_state"] == {"say": {"success": battery}}
    assert meta["list_contacts"] is None
    assert {name: v.role for name, v in voice.items() if v.role} == {
        "navigate_to": "motion", "return_to_dock": "motion", "stop_robot": "stop", "get_robot_pose": "pose",
        "cancel_navigation": "cancel"}


def test_a_malformed_voice_section_is_ignored_with_a_warning(caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING):
        assert voice_section("dance", {META_KEY: {"role": "tango"}}) is None
    assert "dance" in caplog.text
    assert voice_section("dance", None) is None and voice_section("dance", {"other": 1}) is None
    section = voice_section("halt", {META_KEY: {"role": "stop"}})
    assert section is not None and section.role == "stop"
