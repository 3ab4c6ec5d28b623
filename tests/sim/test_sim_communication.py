"""Nodes `communication` and `projector`."""

from __future__ import annotations

from typing import Any

import pytest

from robovoice.errors import InvalidArgumentsError, RobotFailure
from robovoice.middleware.memory import MemoryMiddleware
from robovoice.sim.communication import find_contact

from .sim_testkit import StartRobot

CONTACTS = [{"name": "Anna", "relation": "daughter"}, {"name": "Ben", "relation": "son"},
            {"name": "Clara", "relation": "neighbour"}, {"name": "Dr. Weber", "relation": "family doctor"}]


@pytest.mark.parametrize(
    ("text", "name"),
    [
        ("Anna", "Anna"), ("anna", "Anna"), (" ANNA ", "Anna"), ("my daughter", "Anna"),
        ("ben", "Ben"), ("Clara", "Clara"), ("the neighbor", "Clara"),
        ("Dr. Weber", "Dr. Weber"), ("Dr Weber", "Dr. Weber"), ("Doctor Weber", "Dr. Weber"),
        ("weber", "Dr. Weber"), ("the doctor", "Dr. Weber"), ("dr. weber", "Dr. Weber"),
        ("Anna beta", "Anna"), ("Ben ji", "Ben"), ("Clara dear", "Clara"),  # a word of endearment or respect after
        ("Sir Ben", "Ben"), ("Ma'am Anna", "Anna"), ("Auntie Clara", "Clara"),  # a title before (audio test v61)
        ("Tito Ben", "Ben"), ("Ate Clara", "Clara"), ("Doc Weber", "Dr. Weber"), ("Anna po", "Anna"),  # (text v78)
        ("Mommy Anna", "Anna"),  # (text v80)
        ("Clara-ssi", "Clara"), ("Ben samchon", "Ben"), ("Ben samchon, jebal", "Ben"),  # Korean (text v105)
        ("Clara-ben", "Clara"), ("Anna-behn", "Anna"),  # Gujarati's sister, joined to the name (text v132)
    ],
)
def test_contacts_are_matched_tolerantly(text: str, name: str) -> None:
    contact = find_contact(text)
    assert contact is not None
    assert contact.name == name


@pytest.mark.parametrize("text", ["Bob", "Annabel", "Dr. Miller", "dr", "", "mum", "Weber Anna", "beta", "Bob ji",
                                  "Sir Bob", "sir", "my son's friend Tom", "Anna and Ben",
                                  "Anna Ben"])
def test_unknown_contacts_are_not_guessed(text: str) -> None:
    assert find_contact(text) is None


async def test_call_lifecycle(bus: MemoryMiddleware, start: StartRobot, make_inbox: Any) -> None:
    robot = await start(nodes=["communication"])
    calls = await make_inbox("call_state", robot.clock)
    assert await bus.call("communication", "list_contacts", {}, timeout=1) == {"contacts": CONTACTS}

    started = await bus.call("communication", "start_call", {"contact": "Doctor Weber"}, timeout=1)
    assert started == {"in_call": True, "contact": "Dr. Weber", "relation": "family doctor"}
    assert robot.state.call_contact == "Dr. Weber" and robot.state.in_call
    await calls.wait_for(lambda items: any(i.value["contact"] == "Dr. Weber" for i in items))
    # the remote participant talks now and then: the voice pipeline sees it like playback
    await calls.wait_for(lambda items: any(i.value["remote_speaking"] for i in items))
    await calls.wait_for(lambda items: not items[-1].value["remote_speaking"])
    state = await bus.call("communication", "get_call_state", {}, timeout=1)
    assert state["in_call"] is True and state["contact"] == "Dr. Weber" and state["duration_s"] > 0

    again = await bus.call("communication", "start_call", {"contact": "weber"}, timeout=1)
    assert again["already_in_call"] is True
    with pytest.raises(RobotFailure) as busy:
        await bus.call("communication", "start_call", {"contact": "Anna"}, timeout=1)
    assert busy.value.code == "busy"
    assert "Dr. Weber" in busy.value.message
    assert busy.value.details == {"in_call_with": "Dr. Weber", "requested": "Anna"}

    ended = await bus.call("communication", "end_call", {}, timeout=1)
    assert ended["ended"] is True and ended["contact"] == "Dr. Weber"
    assert robot.state.call_contact is None and not robot.state.remote_speaking
    await calls.wait_for(lambda items: items[-1].value == {"in_call": False, "contact": None,
                                                           "remote_speaking": False, "duration_s": None})
    with pytest.raises(RobotFailure) as none:
        await bus.call("communication", "end_call", {}, timeout=1)
    assert none.value.code == "not_in_call"


async def test_unknown_contact(bus: MemoryMiddleware, start: StartRobot) -> None:
    robot = await start(nodes=["communication"])
    with pytest.raises(RobotFailure) as err:
        await bus.call("communication", "start_call", {"contact": "Bob"}, timeout=1)
    body = err.value.to_dict()
    assert body["error"] == "unknown_contact"
    assert body["details"]["contacts"] == CONTACTS
    assert "name the contacts you can call" in body["hint"]
    assert "Anna" in body["message"] and "Dr. Weber" in body["message"]
    assert not robot.state.in_call


async def test_projector_state_is_kept(bus: MemoryMiddleware, start: StartRobot) -> None:
    robot = await start(nodes=["projector"])
    assert await bus.call("projector", "get_state", {}, timeout=1) == {"on": False}
    assert await bus.call("projector", "set_power", {"on": True}, timeout=1) == {"on": True, "changed": True}
    assert await bus.call("projector", "set_power", {"on": True}, timeout=1) == {"on": True, "changed": False}
    assert robot.state.projector_on is True
    assert await bus.call("projector", "get_state", {}, timeout=1) == {"on": True}
    with pytest.raises(InvalidArgumentsError):
        await bus.call("projector", "set_power", {"on": "yes"}, timeout=1)
    off = await bus.call("projector", "set_power", {"on": False}, timeout=1)
    assert off == {"on": False, "changed": True}
    assert robot.state.projector_on is False
