"""Issue 11: the model once spoke the gate's hint aloud. Text meant for the model (its system
prompt, the gate's hints, a tool error's hint) is never words for the person: a sentence that
reproduces it is unspeakable (`speech_guard.unspeakable_in`), whatever the wording of the hint."""

from __future__ import annotations

import json
from typing import Any

import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.events import SentenceReady, ToolCalled, ToolReturned, TurnEvent
from robovoice.assistant.gate import NOT_REQUESTED, model_only_texts, refusal_reasons
from robovoice.assistant.loop import Assistant
from robovoice.assistant.prompt import GUESSED_HINT, SYSTEM_PROMPT
from robovoice.assistant.speech_guard import (
    MODEL_ONLY,
    ModelOnlyText,
    TurnActions,
    claimed_action_in,
    figures_in,
    in_first_person,
    invented_figure_in,
    speakable,
    unspeakable_in,
)
from robovoice.assistant.turn_rules import wordless_reply
from robovoice.config import RobotConfig
from robovoice.llm.fake_server import CallbackReply, FakeOpenAIServer, ScriptedCall, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from tests.assistant.scripted import scripted_turn

SIM = RobotConfig(address="sim://?speed=50")

# replies a person should hear: some follow a hint closely, none reads one out
REPLIES = [
    "All right, I will stay here.",
    "I do not know that place.",
    "I know the kitchen, the bedroom and the front door.",
    "I can switch the projector on if you ask me to.",
    "Which room do you mean?",
    "The projector is now on.",
    "I am a small helper robot.",
    "Sorry, I did not catch that.",
    "Your son Ben sounds lovely.",
]


@pytest.mark.parametrize("hint", model_only_texts())
def test_every_gate_hint_read_out_is_unspeakable_whole_or_in_part(hint: str) -> None:
    assert unspeakable_in(hint) is not None and speakable(hint) is None
    for sentence in hint.split(". "):  # each of its sentences on its own, as the splitter hands them on
        assert speakable(sentence) is None, sentence


def test_the_loops_step_hints_read_out_are_unspeakable() -> None:
    """A compound request gets "One thing at a time, in order. First: …" as a user message the
    person never said; a small model may read it back."""
    assert speakable("Now do the next thing I asked: switch the projector on.") is None
    assert speakable("One thing at a time, in order.") is None
    assert speakable("I'm on my way to the kitchen, one step at a time.") is not None


@pytest.mark.parametrize("reply", REPLIES)
def test_replies_that_follow_a_hint_are_spoken(reply: str) -> None:
    assert unspeakable_in(reply) is None and speakable(reply) == reply


def test_the_system_prompt_and_any_tool_hint_read_out_are_unspeakable() -> None:
    for sentence in SYSTEM_PROMPT.split(". "):
        if len(sentence.split()) >= 3:
            assert speakable(sentence) is None, sentence
    # a robot's own tool error hint, not known in advance: naming the person as "the user" gives it away
    assert speakable("Please tell the user which one they mean.") is None
    # ... and once the hint is known, a copy of it without that name too
    hint = "name the known places and ask which one they mean"
    assert speakable("Name the known places and ask which one they mean.") is not None
    known = ModelOnlyText([hint])
    assert speakable("Name the known places and ask which one they mean.", known) is None
    assert speakable("I know the kitchen and the bedroom.", known) is not None


def test_what_a_tool_hint_tells_the_model_to_say_is_speakable_and_its_instructions_are_not() -> None:
    known = ModelOnlyText()
    known.add_hint("tell the user the robot cannot get to the balcony (door closed)")
    known.add_hint("tell the user you do not know that place, name the known places and ask which one they mean")
    known.add_hint("tell the user the battery is too low and offer to return to the charging dock")
    assert speakable("The robot cannot get to the balcony (the balcony door is closed).", known) is not None
    assert speakable("I do not know that place.", known) is not None
    assert speakable("Name the known places and ask which one they mean.", known) is None
    assert speakable("I offer to return to the charging dock.", known) is None
    assert speakable("Tell the user the robot cannot get there.", known) is None  # "the user" gives it away
    # a hint that tells the model nothing to say is model-only whole
    known.add_hint("the robot has stopped; ask where to go next")
    assert speakable("The robot has stopped; ask where to go next.", known) is None


def test_a_tool_read_back_is_unspeakable_and_a_true_answer_near_its_description_is_not() -> None:
    """Seen from Qwen2.5-Coder under its own GGUF template (llama-server, llama-cpp-python): after a
    look-up hint it copied the tool's definition out, one sentence at a time."""
    description = "The robot's battery now: percent charged, whether it is charging, and the voltage."
    known = MODEL_ONLY.copy()
    known.add(description, short_copies=False)
    assert speakable("<tools>", known) is None
    assert speakable("```", known) is None and speakable('{{"name": "return_to_dock"}}', known) is None
    assert speakable('{"type": "function", "function": {"name": "get_battery_state"', known) is None
    assert speakable("whether it is charging, and the voltage.", known) is None
    assert speakable("It is charging.", known) == "It is charging."  # three words of it, but true
    assert speakable("My battery is at 80 percent and it is charging.", known) is not None


def echo_the_hint(request: Any) -> Any:
    """A small model that reads the refusal's hint out, then says something sensible."""
    tool = request.messages[-1]
    if tool.get("role") != "tool":
        return ToolCallReply((ScriptedCall("navigate_to", {"target": "bathroom"}),))
    hint = json.loads(tool["content"])["hint"]
    return TextReply(f"{hint} Not today.")


async def _turn_with(reply: Any, text: str = "Did you go to the bathroom today?") -> tuple[Any, list[str], str]:
    """(A question: talk or a request declined alone gets the robot's own line, no model step.)"""
    said: list[str] = []

    def on_event(event: TurnEvent) -> None:
        if isinstance(event, SentenceReady):
            said.append(event.text)

    async with connect_robot(SIM) as robot, FakeOpenAIServer(default=CallbackReply(reply)) as server:
        backend = OpenAICompatBackend(server.base_url, server.model)
        try:
            result = await Assistant(backend, robot.tools).turn(text, observer=on_event)
        finally:
            await backend.aclose()
    hint = json.loads(server.requests[1].messages[-1]["content"])["hint"]
    return result, said, hint


async def test_a_model_that_echoes_the_gate_hint_has_only_its_own_words_said() -> None:
    result, said, hint = await _turn_with(echo_the_hint)
    assert [o.error for o in result.outcomes] == [NOT_REQUESTED]
    assert hint not in result.reply and hint.split(". ")[0] not in " ".join(said)  # the model read it out
    assert said == ["Not today."] and result.reply == "Not today."


def only_the_hint(request: Any) -> Any:
    """A small model that answers a refusal with nothing but its hint."""
    tool = request.messages[-1]
    if tool.get("role") != "tool":
        return ToolCallReply((ScriptedCall("navigate_to", {"target": "bathroom"}),))
    return TextReply(json.loads(tool["content"])["hint"])


async def test_a_reply_that_is_nothing_but_the_hint_ends_the_turn_with_words_of_the_robots_own() -> None:
    """Before, the voice layer withheld such a reply and the person heard nothing at all."""
    result, said, _ = await _turn_with(only_the_hint)
    assert [o.error for o in result.outcomes] == [NOT_REQUESTED]
    assert said == [wordless_reply(result.outcomes, ())] and result.reply == said[0]
    assert said == ["I'm not sure. Could you ask me another way?"]  # the refusal's reason: a question


@pytest.mark.parametrize("reason", refusal_reasons())
def test_every_refusal_reason_has_words_of_the_robots_own(reason: str) -> None:
    refused = ToolReturned("c1", "navigate_to", "{}", True, 0.0, NOT_REQUESTED,
                           {"error": NOT_REQUESTED, "details": {"tool": "navigate_to", "reason": reason}})
    reply = wordless_reply([refused], ())
    assert not reply.startswith("Sorry, I'm not sure what you would like") and speakable(reply) == reply


@pytest.mark.parametrize("sentence", [
    "The projector is now on.", "I have turned on the projector.", "I've started a video call with Anna.",
    "Calling Anna now.", "On my way to the kitchen.", "Done.", "OK, done!", "Sure, heading to the hallway.",
    "The projector has been switched on.", "I\u2019m now calling Ben.", "The video call with Ben has started.",
    "The robot is now at the front door.", "I am in a video call with Clara now.", "I am in the living room now.",
])
def test_a_sentence_claiming_an_action_is_recognised(sentence: str) -> None:
    assert claimed_action_in(sentence) is not None


@pytest.mark.parametrize("sentence", [
    "All right, I won't.", "I haven't turned it on.", "I will not drive anywhere.", "Which one do you mean?",
    "Your battery is at 84 percent.", "I can switch the projector on if you like.", "The projector is off.",
    "Okay, I will stay here.", "I'm glad Ben phoned.", "Yes, I can do that when you ask me to.",
    "I havent turned it on.", "I dont want to drive to the front door.",
])
def test_a_sentence_that_claims_nothing_or_denies_is_not(sentence: str) -> None:
    assert claimed_action_in(sentence) is None


def _turn(*calls: tuple[str, dict[str, object], str | None]) -> TurnActions:
    """The actions of a turn: (tool, arguments, error) per call; the look-ups are read-only."""
    called = [ToolCalled(f"c{i}", name, dict(arguments)) for i, (name, arguments, _) in enumerate(calls)]
    returned = [ToolReturned(f"c{i}", name, "", error is not None, 1.0, error)
                for i, (name, _, error) in enumerate(calls)]
    return TurnActions(called, returned, {"get_robot_pose", "get_camera_image"},
                       {"navigate_to", "return_to_dock", "set_projector_power", "start_video_call"})


@pytest.mark.parametrize(("actions", "sentence", "false"), [
    (_turn(), "Heading to the kitchen now.", False),  # before any call: it may announce the call that follows
    (_turn(("get_camera_image", {}, None)), "The robot is now at the front door.", True),  # only a look-up ran
    (_turn(("navigate_to", {"target": "front door"}, None)), "I am now at the front door.", False),
    (_turn(("set_projector_power", {"on": True}, None), ("start_video_call", {"contact": "Ben"}, "not_requested")),
     "The video call with Ben has started.", True),  # names only the call that did not run
    (_turn(("set_projector_power", {"on": True}, None), ("start_video_call", {"contact": "Ben"}, "not_requested")),
     "The projector is now on.", False),
    (_turn(("navigate_to", {"target": "garage"}, "unknown_target")), "On my way to the garage.", True),
    # names an action never called, after another ran (text v19: a drive, then "the projector is now on")
    (_turn(("navigate_to", {"target": "bathroom"}, None)), "The projector is now on.", True),
    (_turn(("navigate_to", {"target": "bathroom"}, None)), "I am now in the bathroom.", False),
    (_turn(("navigate_to", {"target": "bedroom"}, None)), "I am in the bedroom now.", False),
    # dev clip rg-32 ("bring men" heard): the second drive was refused, and the model said it had arrived
    (_turn(("navigate_to", {"target": "bedroom"}, None), ("navigate_to", {"target": "living room"}, "not_requested")),
     "I am in the living room now.", True),
    (_turn(("navigate_to", {"target": "bathroom"}, None), ("set_projector_power", {"on": True}, None)),
     "The projector is now on.", False),
    (_turn(("start_video_call", {"contact": "Ben"}, "not_requested")), "I won't call Ben.", False),  # a denial
    # every call refused: what the robot is doing was never looked up, and is a guess
    (_turn(("return_to_dock", {}, "not_requested")), "I am already at my charging dock.", True),
    (_turn(("set_projector_power", {"on": True}, "not_requested")), "The projector is not turned on.", True),
    (_turn(("navigate_to", {"target": "kitchen"}, "not_requested")), "I'm not moving.", True),
    (_turn(("navigate_to", {"target": "kitchen"}, "not_requested")), "I'm not sure what you mean.", False),
    # a failure's own message may say the state ("already in a call"); a look-up found it
    (_turn(("start_video_call", {"contact": "Ben"}, "busy")), "You are already in a call.", False),
    (_turn(("get_robot_pose", {}, None), ("navigate_to", {"target": "kitchen"}, "not_requested")),
     "I am at my charging dock.", False),
])
def test_a_claim_is_false_when_the_turn_did_not_do_it(actions: TurnActions, sentence: str, false: bool) -> None:
    assert (actions.false_claim(sentence) is not None) is false


@pytest.mark.parametrize(("sentence", "invented"), [
    ("The robot's battery is at 80% and it is charging.", "80%"),  # no look-up was made
    ("It is 5.3 meters away and will take 10.6 seconds.", "5.3 meters"),
    ("My battery is at 83 percent.", None),  # 83.33 rounded
    ("I am facing 90 degrees.", None),  # 1.5708 rad
    ("Two plus two is 4, and I have 3 friends.", None),  # not a measured figure
])
def test_a_measured_figure_must_come_from_the_conversation(sentence: str, invented: str | None) -> None:
    known = figures_in(['{"percent": 83.33, "charging": true}', '{"theta": 1.5708}'])
    assert invented_figure_in(sentence, known) == invented


async def test_a_battery_level_the_model_never_looked_up_is_not_said_but_looked_up() -> None:
    """A guessed figure is held back, and the model is asked once more, offered only the look-ups,
    to find it out (a 1.5B model under a GGUF chat template answers from the tool's description)."""
    result, server = await scripted_turn([
        TextReply("Your battery is at 80 percent."),
        ToolCallReply((ScriptedCall("get_battery_state", {}),)),
        TextReply("My battery is at 95 percent."),  # wrong again: the tool's own phrase says it
    ], "How much battery have you got?")
    assert [c.name for c in result.calls] == ["get_battery_state"]
    level = result.outcomes[0].result["value"]["percent"]  # type: ignore[index]
    assert result.reply.startswith(f"My battery is at {round(level)} percent")  # the manifest's phrase
    retry = server.requests[1]
    assert retry.last_user_text == GUESSED_HINT
    assert retry.tool_names and "navigate_to" not in retry.tool_names  # only look-ups on the retry
    assert "get_battery_state" in retry.tool_names
    assert "80 percent" not in json.dumps(retry.messages)  # the guess is not shown back as said


async def test_a_guess_is_looked_up_once_only() -> None:
    result, server = await scripted_turn([
        TextReply("Your battery is at 80 percent."),
        TextReply("It is at 70 percent."),
    ], "How much battery have you got?")
    assert len(server.requests) == 2 and not result.calls
    assert "percent" not in result.reply and result.reply  # neither guess said, but an answer


@pytest.mark.parametrize(("sentence", "spoken"), [
    ("The robot's battery is at 94% and charging.", "My battery is at 94% and charging."),
    ("The robot is already at its charging dock.", "I am already at my charging dock."),
    ("The robot can drive to the bathroom or the kitchen.", "I can drive to the bathroom or the kitchen."),
    ("Right now the robot isn't moving.", "Right now I am not moving."),
    ("The robot did not go to the front door.", "I did not go to the front door."),
    ("The robot sees a small image of the room.", "I see a small image of the room."),
    ("The robot needs to charge, so the robot goes to its dock.", "I need to charge, so I go to my dock."),
    ("The robot was in the hallway.", "I was in the hallway."),
    ("The robot took a picture and captured an image.", "I took a picture and captured an image."),
    ("The robot went to the kitchen.", "I went to the kitchen."),
    ("The robot arms are in the kitchen.", "The robot arms are in the kitchen."),  # not its own verb
    ("I am in the kitchen.", "I am in the kitchen."),  # already its own voice
    ("The robot vacuum is in the hallway.", "The robot vacuum is in the hallway."),  # another robot
    ("Please tell the robot which place you mean.", "Please tell me which place you mean."),  # the person's doing
    # the second person, as the person would say it to the robot (texts v27 and v28)
    ("Your battery is currently at 83.8% and is charging.", "My battery is currently at 83.8% and is charging."),
    ("You are currently at the charging dock, facing north.", "I am currently at the charging dock, facing north."),
    ("Right now you're near the kitchen and your camera sees a table.",
     "Right now I am near the kitchen and my camera sees a table."),
    ("You are in the kitchen, so I will come to you.", "You are in the kitchen, so I will come to you."),  # the person
    ("You are welcome.", "You are welcome."),
])
def test_the_robot_speaks_of_itself_in_the_first_person(sentence: str, spoken: str) -> None:
    assert in_first_person(sentence) == spoken


async def test_the_persons_own_words_read_back_are_not_said() -> None:
    """Text test v15: a small model answered a remark by reading it back to the person ("Dr. Weber
    told me I ought to…"). Six words in a row of this turn's words are not the robot's to say."""
    text = "My grandson tells me the garden looks much tidier since the spring."
    result, _ = await scripted_turn([TextReply("My grandson tells me the garden looks much tidier. How lovely!")], text)
    assert "grandson tells me" not in result.reply
    assert "How lovely!" in result.reply
    result, _ = await scripted_turn([TextReply("The garden sounds lovely.")], text)  # a few of the words: said
    assert result.reply == "The garden sounds lovely."
