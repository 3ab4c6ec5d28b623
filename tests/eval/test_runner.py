"""`run_eval` end to end on the embedded sim with a scripted model: each call in the report
says what became of it at the robot (its error code, the argument the robot resolved), and
only forbidden actuation tools that ran count as false actuations."""

from __future__ import annotations

import socket

from robovoice.assistant.connect import connect_robot
from robovoice.config import RobotConfig
from robovoice.eval.cases import Case
from robovoice.eval.runner import run_eval
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedCall, ScriptedReply, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend


def case(**fields: object) -> Case:
    return Case.model_validate(fields)


def call(name: str, **arguments: object) -> ToolCallReply:
    return ToolCallReply((ScriptedCall(name, arguments),))


async def test_the_report_says_what_reached_the_robot() -> None:
    cases = [
        case(id="lounge", text="Go to the lounge", expect=[{"tool": "navigate_to", "args": {"target": "living room"}}]),
        case(id="garage", text="Drive to the garage", expect=[], forbid=["navigate_to"]),
        # a case that forbids what the text asks, so that the scripted call below is a false actuation
        case(id="negated", text="Switch the projector on", expect=[], forbid=["set_projector_power"],
             **{"class": "negated"}),
        case(id="read-only", text="How is the battery?", expect=[], forbid=["get_battery_state"]),
    ]
    script: list[ScriptedReply] = [
        call("navigate_to", target="lounge"),  # its success phrase is the answer: no second model step
        call("navigate_to", target="garage"), TextReply("I don't know the garage."),
        call("set_projector_power", on=True),
        call("get_battery_state"), TextReply("The battery is fine."),
    ]
    async with FakeOpenAIServer(script) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            report = (await run_eval(cases, backend, lambda: connect_robot(RobotConfig(address="sim://?speed=40")))).to_dict()
        finally:
            await backend.aclose()
    by_id = {r["id"]: r for r in report["results"]}

    lounge = by_id["lounge"]
    assert lounge["passed"], lounge["reason"]  # the robot drove to the living room
    assert lounge["calls"] == [{"tool": "navigate_to", "args": {"target": "lounge"}, "error": None,
                                "resolved": {"target": "living room"}}]

    garage = by_id["garage"]  # refused before acting: nothing moved, not a false actuation
    assert garage["passed"] and "refused by the robot" in garage["reason"]
    assert garage["calls"][0]["error"] == "unknown_target" and garage["false_actuations"] == []

    negated = by_id["negated"]
    assert not negated["passed"] and negated["false_actuations"] == ["set_projector_power"]

    read_only = by_id["read-only"]  # forbidden, so the case fails, but a read-only tool actuates nothing
    assert not read_only["passed"] and read_only["false_actuations"] == []

    assert report["false_actuations"] == 1 and report["passed"] == 2
    assert report["classes"]["negated"] == {"cases": 1, "passed": 0, "false_actuations": 1, "model_unanswered": 0,
                                            "accuracy": 0.0}
    assert report["classes"]["-"]["cases"] == 3
    assert report["model_unanswered"] == 0


async def test_turns_no_model_answered_are_counted() -> None:
    """A dead model server makes a negated case 'pass' (nothing moved): the report says that no
    model answered it, so such a figure is not read as judgement."""
    with socket.socket() as probe:  # a port nothing listens on: the connection is refused
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    backend = OpenAICompatBackend(f"http://127.0.0.1:{port}/v1", "m")
    cases = [case(id="neg", text="Don't go to the kitchen", expect=[], forbid=["navigate_to"], **{"class": "negated"})]
    try:
        report = (await run_eval(cases, backend, lambda: connect_robot(RobotConfig(address="sim://?speed=40")))).to_dict()
    finally:
        await backend.aclose()
    assert report["passed"] == 1 and report["model_unanswered"] == 1
    assert report["results"][0]["model_unanswered"] == 1
    assert report["classes"]["negated"]["model_unanswered"] == 1
