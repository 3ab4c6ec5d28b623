"""The check before acting and compound requests, in the real tool loop: a scripted model
behind a real HTTP server, the embedded sim behind the real MCP server."""

from __future__ import annotations

import pytest

from robovoice.assistant.gate import NOT_REQUESTED
from robovoice.assistant.loop import Assistant, TurnResult
from robovoice.llm.fake_server import ScriptedCall, ScriptedReply, TextReply, ToolCallReply
from tests.assistant.scripted import scripted_sim, scripted_turn


def call(name: str, **arguments: object) -> ToolCallReply:
    return ToolCallReply((ScriptedCall(name, arguments),))


def made(result: TurnResult) -> list[tuple[str, str | None]]:
    """Each call of the turn with its error (None: it ran; `NOT_REQUESTED`: refused)."""
    return [(c.name, o.error) for c, o in zip(result.calls, result.outcomes, strict=True)]


async def test_a_negated_request_never_reaches_the_robot() -> None:
    """Nothing else was asked: the robot's own line answers at once, with no second model step
    (on the embedded model that step took 5-7 s and was mostly given the same line)."""
    async with scripted_sim(
        [call("navigate_to", target="bathroom"), TextReply("All right, I'll stay here.")]
    ) as (robot, server, backend):
        result = await Assistant(backend, robot.tools).turn("Don't drive to the bathroom just now.")
        assert robot.sim is not None
        assert not robot.sim.state.moving and robot.sim.state.nearest_place != "bathroom"
    assert [o.error for o in result.outcomes] == [NOT_REQUESTED]
    assert result.reply == "All right, I won't." and len(server.requests) == 1
    assert "not to do this now" in result.outcomes[0].text  # the refusal says why, for any later step


async def test_talk_is_answered_at_once_and_a_question_by_the_model() -> None:
    """Talk that mentions a place: the robot's own "I see." at once. A question the model took
    for an order: the model words the answer (it may have looked something up)."""
    async with scripted_sim(
        [call("navigate_to", target="bathroom"), call("navigate_to", target="bathroom"),
         TextReply("I have not been there today.")]
    ) as (robot, server, backend):
        talk = await Assistant(backend, robot.tools).turn("My daughter rang from her bathroom this morning.")
        question = await Assistant(backend, robot.tools).turn("Did you go to the bathroom this morning?")
    assert [o.error for o in talk.outcomes] == [NOT_REQUESTED] and talk.reply == "I see."
    assert [o.error for o in question.outcomes] == [NOT_REQUESTED]
    assert question.reply == "I have not been there today."
    tool_message = server.requests[2].messages[-1]  # the model was told why, with a hint it can follow
    assert tool_message["role"] == "tool" and "asked a question" in tool_message["content"]


async def test_without_the_checks_the_same_call_reaches_the_robot() -> None:
    """`Assistant(checks=False)` is the baseline `robovoice bench voice local --no-checks` measures
    against (issue 11's latency bar): no check before acting, so the refused drive runs."""
    async with scripted_sim(
        [call("navigate_to", target="bathroom"), TextReply("On my way.")]
    ) as (robot, _server, backend):
        result = await Assistant(backend, robot.tools, checks=False).turn("Don't drive to the bathroom just now.")
        assert robot.sim is not None and robot.sim.state.nearest_place == "bathroom"
    assert [o.error for o in result.outcomes] == [None]


@pytest.mark.parametrize(("worded", "said"), [
    ("The projector is now on. Anything else?", "Anything else?"),
    ("Done, the projector has been switched on.", "Yes, I can do that when you ask me to."),  # the refusal's line
])
async def test_after_a_refusal_the_model_never_claims_the_refused_action_done(worded: str, said: str) -> None:
    """A small model words the refused call as done ("The projector is now on."): a false claim
    the person would believe. It is not said; what is true is. (A question that names the
    projector, "are you able to switch on a projector?", gets the robot's own yes, unworded.)"""
    async with scripted_sim(
        [call("set_projector_power", on=True), TextReply(worded)]
    ) as (robot, _server, backend):
        result = await Assistant(backend, robot.tools).turn("Are you able to show my holiday photos nice and big?")
        assert robot.sim is not None and not robot.sim.state.projector_on
    assert result.reply == said


async def test_a_look_up_beside_an_action_is_offered_only_look_ups_then_the_action_follows() -> None:
    """"Which room are you in? After that come to the bedroom.": on the look-up's step only
    read-only tools are offered (the small model drove instead of looking); answered in words,
    the next thing asked still follows."""
    result, server = await scripted_turn([TextReply("I am in the living room."), call("navigate_to", target="bedroom")],
                                         "Which room are you in? After that come to the bedroom.")
    first, second = server.requests[0].tool_names, server.requests[1].tool_names
    assert "get_robot_pose" in first and "navigate_to" not in first and "set_projector_power" not in first
    assert "navigate_to" in second
    assert server.requests[1].last_user_text == "Now do the next thing I asked: come to the bedroom."
    assert [c.name for c in result.calls] == ["navigate_to"]
    assert result.reply.startswith("I am in the living room.")


async def test_a_compound_request_is_carried_out_step_by_step() -> None:
    script: list[ScriptedReply] = [
        call("navigate_to", target="kitchen"),
        call("set_projector_power", on=True),
    ]
    async with scripted_sim(script) as (robot, server, backend):
        result = await Assistant(backend, robot.tools).turn("Go to the kitchen and then switch the projector on.")
        assert robot.sim is not None and robot.sim.state.projector_on
    assert [c.name for c in result.calls] == ["navigate_to", "set_projector_power"]
    # first the model was told to take one thing at a time, after the drive what comes next
    assert server.requests[0].last_user_text == "One thing at a time, in order. First: Go to the kitchen."
    assert server.requests[1].last_user_text == "Now do the next thing I asked: switch the projector on."
    # each action's own phrase said what happened: no model step only to word it
    assert result.reply == "I am in the kitchen now. The projector is now on."
    assert len(server.requests) == 2


async def test_a_step_the_robot_could_not_do_is_said_before_the_next_thing_asked() -> None:
    """"Drive out to the balcony, then turn on the projector.": the drive fails (the door is
    closed). The projector's own phrase would have been the whole answer, and the person would
    never hear the drive failed: the model words the failure first (offered no tools), then
    does the next thing asked. The hint's content, said, is the answer, not a hint read out."""
    script: list[ScriptedReply] = [
        call("navigate_to", target="balcony"),
        TextReply("The robot cannot get to the balcony (the balcony door is closed)."),
        call("set_projector_power", on=True),
    ]
    async with scripted_sim(script) as (robot, server, backend):
        result = await Assistant(backend, robot.tools).turn("Drive out to the balcony, then turn on the projector.")
        assert robot.sim is not None and robot.sim.state.projector_on
    assert [o.error for o in result.outcomes] == ["unreachable", None]
    assert server.requests[1].tool_names == [] and server.requests[1].messages[-1]["role"] == "tool"
    assert server.requests[2].last_user_text == "Now do the next thing I asked: turn on the projector."
    assert result.reply == "I cannot get to the balcony (the balcony door is closed). The projector is now on."


async def test_what_the_robot_said_is_not_said_again() -> None:
    """Audio v16's compound-6 answered "I am in the bathroom now. I am in the bathroom now.": the
    drive's phrase, then the model's words before its next call, the same sentence."""
    script: list[ScriptedReply] = [
        call("navigate_to", target="kitchen"),
        ToolCallReply((ScriptedCall("set_projector_power", {"on": True}),), text="I am in the kitchen now."),
    ]
    result, _ = await scripted_turn(script, "Go to the kitchen and then switch the projector on.")
    assert result.reply == "I am in the kitchen now. The projector is now on."


async def test_quit_said_during_a_drive_lets_its_cancel_run() -> None:
    """Audio v16's stop-2: "hold it, quit driving!" heard as "Oh, it's quit driving." reads as
    talk; the model's cancel was refused, and the robot drove on."""
    async with scripted_sim([call("cancel_navigation"), TextReply("All right.")]) as (robot, _server, backend):
        assert robot.sim is not None
        await robot.sim.apply_setup("driving")
        result = await Assistant(backend, robot.tools).turn("Oh, it's quit driving.")
        assert not robot.sim.state.moving
    assert [o.error for o in result.outcomes] == [None]


async def test_a_stop_is_refused_only_where_the_robot_stands_still() -> None:
    """"Hold it! Stay put!" reads as "carry on as you are" (a statement), and a drive asked in
    the same words would be refused; the robot's stop tool (voice role "stop") is not while the
    robot moves. Where its pose snapshot says it stands still, a stop the words never asked for
    ("Wait, don't call anyone.") is refused: it would do nothing the person asked."""
    async with scripted_sim(
        [call("stop_robot"), call("stop_robot")]  # the first is said by its phrase, the second by the refusal's
    ) as (robot, _server, backend):
        assert robot.sim is not None
        await robot.sim.apply_setup("driving")
        assert robot.sim.state.moving
        result = await Assistant(backend, robot.tools).turn("Hold it! Stay put!")
        assert not robot.sim.state.moving
        assert [o.error for o in result.outcomes] == [None]
        standing = await Assistant(backend, robot.tools).turn("Wait, don't call anyone.")
    assert [o.error for o in standing.outcomes] == [NOT_REQUESTED]


async def test_never_mind_cancels_a_drive_under_way_and_nothing_when_none_is() -> None:
    """"Never mind" asks for nothing new: during a drive the robot's cancel tool (voice role
    "cancel") still runs; with the robot standing still it is refused, and so is any other
    action the model reads into it (a small model switched the projector off)."""
    async with scripted_sim(
        [call("cancel_navigation"), call("cancel_navigation"), call("set_projector_power", on=False)]
    ) as (robot, _server, backend):
        assert robot.sim is not None
        await robot.sim.apply_setup("driving+projector_on")
        driving = await Assistant(backend, robot.tools).turn("Oh, never mind, forget it.")
        assert not robot.sim.state.moving
        standing = await Assistant(backend, robot.tools).turn("Never mind about that.")
        projector = await Assistant(backend, robot.tools).turn("Never mind, not tonight.")
        assert robot.sim.state.projector_on
    assert [o.error for o in driving.outcomes] == [None]
    assert [o.error for o in standing.outcomes] == [NOT_REQUESTED]
    assert [o.error for o in projector.outcomes] == [NOT_REQUESTED]


async def test_keep_going_dont_stop_during_a_drive_stops_nothing() -> None:
    """The words say to carry on: the stop and cancel tools stay refused while the robot moves
    (test v8: "Keep going, keep going, don't stop - I was only talking to the cat." cancelled)."""
    async with scripted_sim(
        [call("cancel_navigation"), call("stop_robot")]  # each refusal answered by "All right, I won't."
    ) as (robot, _server, backend):
        assert robot.sim is not None
        await robot.sim.apply_setup("driving")
        cancelled = await Assistant(backend, robot.tools).turn("Keep going, don't stop, I'm talking to the dog.")
        stopped = await Assistant(backend, robot.tools).turn("No need to stop, carry on.")
        assert robot.sim.state.moving
    assert [o.error for o in cancelled.outcomes] == [NOT_REQUESTED]
    assert [o.error for o in stopped.outcomes] == [NOT_REQUESTED]


async def test_a_tool_errors_hint_read_out_is_not_said() -> None:
    """The robot's error hints are for the model ("tell the user you do not know that place,
    name the known places and ask which one they mean"); a small model read one out."""
    result, _ = await scripted_turn(
        [call("navigate_to", target="garage"),
         TextReply("I do not know that place. Name the known places and ask which one they mean.")],
        "Go to the garage.")
    assert [o.error for o in result.outcomes] == ["unknown_target"]
    assert result.reply == "I do not know that place."


async def test_a_tool_beside_a_request_for_another_is_refused_and_the_model_tries_again() -> None:
    """"go and get yourself plugged in" and the model switches the projector on: the call does
    not fit the request (`fit`), never reaches the robot, and the model is told what fits."""
    async with scripted_sim(
        [call("set_projector_power", on=True), call("return_to_dock"), TextReply("Off I go.")]
    ) as (robot, server, backend):
        result = await Assistant(backend, robot.tools).turn("You look worn out, go and get yourself plugged in.")
        assert robot.sim is not None and not robot.sim.state.projector_on
        assert robot.sim.state.nearest_place == "charging dock"
    assert made(result) == [
        ("set_projector_power", NOT_REQUESTED), ("return_to_dock", None)]
    tool_message = server.requests[1].messages[-2]  # then the request once more (`turn_rules.refit`)
    assert tool_message["role"] == "tool" and "or return_to_dock." in tool_message["content"]
    offered = server.requests[1].tool_names  # the request asked once more: only what fits
    assert sorted(offered) == ["navigate_to", "return_to_dock"]


async def test_a_claim_of_a_refused_call_beside_an_action_that_ran_is_not_said() -> None:
    """The projector ran, the call was refused (nobody in the request is "him"), and the model
    says both happened: the call's sentence is false and held back, the projector's is said
    (once), and the robot asks whom it should call."""
    result, _ = await scripted_turn(
        [call("set_projector_power", on=True), call("start_video_call", contact="Anna"),
         TextReply("The projector is now on. The video call with Anna has started.")],
        "Put the projector on and then ring him.")
    assert [o.error for o in result.outcomes] == [None, NOT_REQUESTED]
    assert result.reply == "The projector is now on. Which one do you mean: Anna, Ben, Clara or Dr. Weber?"


async def test_a_call_to_someone_nobody_named_is_asked_about_not_made_and_the_answer_is_acted_on() -> None:
    """"Put me on a video call": the model picks Anna. The call is refused, and the robot asks
    whom, naming the contacts, without a second model step (asked again, the embedded model
    made the same call). The person's answer is the next turn's request."""
    script: list[ScriptedReply] = [call("start_video_call", contact="Anna"), call("start_video_call", contact="Ben")]
    async with scripted_sim(script) as (robot, server, backend):
        assistant = Assistant(backend, robot.tools)
        asked = await assistant.turn("Put me on a video call, would you?")
        assert robot.sim is not None and robot.sim.state.call_contact is None
        assert len(server.requests) == 1
        answered = await assistant.turn("Ben, please.")
        assert robot.sim.state.call_contact == "Ben"
    assert [o.error for o in asked.outcomes] == [NOT_REQUESTED]
    assert asked.reply == "Which one do you mean: Anna, Ben, Clara or Dr. Weber?"
    assert [(c.name, c.arguments) for c in answered.calls] == [("start_video_call", {"contact": "Ben"})]


async def test_after_a_declined_call_is_refused_the_request_beside_it_is_done() -> None:
    """"Please don't switch the projector on. I only want to talk to Dr. Weber.": the model
    first switches the projector (refused as declined); told then to do what was asked, it
    makes the call (audio test v4: told only why, it left the request undone)."""
    script: list[ScriptedReply] = [call("set_projector_power", on=False), call("start_video_call", contact="Dr. Weber")]
    async with scripted_sim(script) as (robot, server, backend):
        result = await Assistant(backend, robot.tools).turn(
            "Please don't switch the projector on. I only want to talk to Dr. Weber.")
        assert robot.sim is not None and robot.sim.state.call_contact == "Dr. Weber"
    assert made(result) == [
        ("set_projector_power", NOT_REQUESTED), ("start_video_call", None)]
    assert server.requests[1].last_user_text == "Now do the next thing I asked: I only want to talk to Dr. Weber."


async def test_a_refused_call_made_again_is_not_run_and_the_next_thing_asked_is_done() -> None:
    # a garbled first step (Whisper's "Join the project to look" for "turn the projector off"):
    # the model keeps driving to the kitchen, which nobody named; the dock after it is still done
    script: list[ScriptedReply] = [call("navigate_to", target="kitchen"), call("navigate_to", target="kitchen"),
                                   call("return_to_dock"), TextReply("unused")]
    async with scripted_sim(script) as (robot, server, backend):
        result = await Assistant(backend, robot.tools).turn(
            "Join the project to look and then get yourself back on your charger.")
        assert robot.sim is not None
        assert robot.sim.state.nearest_place == "charging dock"
    assert made(result) == [
        ("navigate_to", NOT_REQUESTED), ("return_to_dock", None)]  # the repeat was not run
    assert len(server.requests) == 3
    hint = server.requests[2].messages[-1]
    assert hint["role"] == "user" and "get yourself back on your charger" in hint["content"]


async def test_the_action_just_done_made_again_is_not_run_and_not_said_twice() -> None:
    # text test v27: "Go on then" read as a step of its own, so the model, told the next thing
    # asked ("take yourself off to the bedroom"), drove to the bedroom a second time ("go on"
    # before a request is no step now; "Get going" still is)
    script: list[ScriptedReply] = [call("navigate_to", target="bedroom"), call("navigate_to", target="bedroom"),
                                   TextReply("unused")]
    async with scripted_sim(script) as (robot, server, backend):
        result = await Assistant(backend, robot.tools).turn(
            "Get going, take yourself off to the bedroom, there's a good lad.")
        assert robot.sim is not None
        assert robot.sim.state.nearest_place == "bedroom"
    assert made(result) == [
        ("navigate_to", None)]  # the repeat was not run
    assert len(server.requests) == 2  # and the turn ended: the arrival was said already
    assert result.reply.count("bedroom") == 1


async def test_an_action_made_again_after_it_failed_is_run() -> None:
    # a failed call is no "done": the model may try it again (the robot decides)
    script: list[ScriptedReply] = [call("end_video_call"), call("end_video_call"), TextReply("There is no call.")]
    result, _server = await scripted_turn(script, "Hang up the call, please.")
    assert [c.name for c in result.calls] == ["end_video_call", "end_video_call"]
    assert result.outcomes[0].is_error


async def test_a_request_for_a_place_only_looked_up_is_asked_for_once_more() -> None:
    """"Wait for me in the bedroom" (the shape of dev nav-hallway-1, look-1…5): the small model
    looks up its pose and answers as if it had gone. A request naming a place an action lists,
    with only look-ups called, is asked for once more right after them, and the drive follows;
    once only, and not after an answer in words alone (a misread question would become an action)."""
    hint = "Now do the next thing I asked: Wait for me in the bedroom."
    result, server = await scripted_turn(
        [call("get_robot_pose"), call("navigate_to", target="bedroom"), TextReply("I'm on my way.")],
        "Wait for me in the bedroom, would you?")
    assert [c.name for c in result.calls] == ["get_robot_pose", "navigate_to"]
    assert server.requests[1].last_user_text == hint
    assert server.requests[1].tool_names == ["navigate_to"]  # offered alone: no second look-up
    result, server = await scripted_turn([TextReply("I'll wait there.")], "Wait for me in the bedroom, would you?")
    assert not result.calls and len(server.requests) == 1
    result, server = await scripted_turn(
        [call("get_robot_pose"), TextReply("I'm in the hallway."), TextReply("Still here.")],
        "Wait for me in the bedroom, would you?")
    assert [c.name for c in result.calls] == ["get_robot_pose"] and len(server.requests) == 2  # once only


async def test_an_irish_would_you_ever_is_asked_for_once_more_like_any_request() -> None:
    """Dev ever-4 and text test v26: "Would you ever nip into the bathroom and check the tap?"
    looked up the pose and the camera and answered. The reading takes it for a request (asks_ever),
    so it is asked for again like one; "would you ever …, do you think?" wonders and is not."""
    result, server = await scripted_turn(
        [call("get_robot_pose"), call("navigate_to", target="bathroom"), TextReply("On my way.")],
        "Would you ever pop into the bathroom and look at the tap for me?")
    assert [c.name for c in result.calls] == ["get_robot_pose", "navigate_to"]
    result, server = await scripted_turn([call("get_robot_pose"), TextReply("I could.")],
                                         "Would you ever pop into the bathroom at all, do you think?")
    assert [c.name for c in result.calls] == ["get_robot_pose"] and len(server.requests) == 2


async def test_a_look_up_or_a_request_naming_no_place_is_not_asked_for_again() -> None:
    """Only a request that names a value an action takes, not said as a question, is asked
    again: "tell me about the kitchen" is a look-up, "have a rest" names nothing an action
    lists, and a "could you …?" is left to the model's own answer."""
    for text in ("Tell me what the kitchen looks like.", "Have a little rest now.",
                 "Could you pop into the bathroom?"):  # said as a question: the model's answer stands
        result, server = await scripted_turn([call("get_camera_image"), TextReply("All right.")], text)
        assert [c.name for c in result.calls] == ["get_camera_image"], text
        assert len(server.requests) == 2, text


async def test_a_request_whose_call_did_not_fit_is_asked_for_once_more_with_what_fits() -> None:
    """Dev dev-single-75 (text test v21: "Off you pop and plug yourself in." rang the doctor,
    refused as not fitting; offered the dock, the model answered "I did not ask for a video
    call."). The request is asked for once more, offered only what fits (text test v26: "…,
    isn't it? Off you go and get yourself topped up.", offered the look-ups too, read the battery
    and answered the remark); once only, and not for a request said as a question."""
    hint = "Now do the next thing I asked: plug yourself in."
    result, server = await scripted_turn(
        [call("start_video_call", contact="Ben"), call("return_to_dock"), TextReply("Off I go.")],
        "Away with you and plug yourself in.")
    assert made(result) == [
        ("start_video_call", NOT_REQUESTED), ("return_to_dock", None)]
    assert server.requests[1].last_user_text == hint
    assert server.requests[1].tool_names == ["return_to_dock"]
    result, server = await scripted_turn(
        [call("start_video_call", contact="Ben"), call("get_battery_state"), TextReply("Sorry.")],
        "Away with you and plug yourself in.")
    assert [o.error for o in result.outcomes] == [NOT_REQUESTED]  # a look-up not offered is not run
    assert "get_battery_state" not in [c.name for c in result.calls]
    assert [m["content"] for m in server.requests[-1].messages].count(hint) == 1  # once only
    result, server = await scripted_turn(  # a call to a tool the step did not offer is not run
        [call("start_video_call", contact="Ben"), call("set_projector_power", on=True), TextReply("Sorry.")],
        "Away with you and plug yourself in.")
    assert [o.error for o in result.outcomes] == [NOT_REQUESTED] and "set_projector_power" not in [
        c.name for c in result.calls]
    result, server = await scripted_turn(
        [call("start_video_call", contact="Ben"), TextReply("I can, yes.")], "Could you plug yourself in?")
    assert len(server.requests) == 2 and server.requests[1].last_user_text == "Could you plug yourself in?"


async def test_a_question_to_come_here_is_asked_again_as_a_drive_to_where_the_person_is() -> None:
    """Text test v46: "I'm in the living room, … Would you come over here to me, please?" and the
    model called Anna (refused as not fitting), then stopped: a request said as a question is
    not asked again. Worded with the place the person said they are in, it is a plain request,
    asked once more (dev here-4)."""
    result, server = await scripted_turn(
        [call("start_video_call", contact="Clara"), call("navigate_to", target="bathroom"), TextReply("Coming.")],
        "I'm in the bathroom, on the stool. Would you come over here to me, please?")
    assert made(result) == [("start_video_call", NOT_REQUESTED), ("navigate_to", None)]
    assert server.requests[1].last_user_text == "Now do the next thing I asked: come to the bathroom."
    assert server.requests[1].tool_names == ["navigate_to"]


async def test_a_look_up_on_the_way_to_an_action_does_not_do_it() -> None:
    """Text test v21: "Switch the projector on once you've got yourself into the living room":
    the model looked up its pose first, the look-up was counted as the drive, and the turn moved
    on to the projector; the drive was never made."""
    result, server = await scripted_turn(
        [call("get_robot_pose"), call("navigate_to", target="living room"), call("set_projector_power", on=True)],
        "Go to the living room, then switch the projector on.")
    assert [c.name for c in result.calls] == ["get_robot_pose", "navigate_to", "set_projector_power"]
    assert server.requests[1].last_user_text == "Now do the next thing I asked: Go to the living room."
    assert server.requests[1].tool_names == ["navigate_to"]  # told alone, the model looked up again
    assert server.requests[2].last_user_text == "Now do the next thing I asked: switch the projector on."
    # a look-up asked for in other words than "tell me" is a step of its own (dev dev-multi-8)
    result, server = await scripted_turn(
        [call("get_battery_state"), call("navigate_to", target="hallway")], "Check your battery and go to the hallway.")
    assert [c.name for c in result.calls] == ["get_battery_state", "navigate_to"]
    assert server.requests[1].last_user_text == "Now do the next thing I asked: go to the hallway."


async def test_a_claim_with_no_call_at_all_is_asked_for_once_more() -> None:
    """Dev checklist-1 and heading-2: "Three jobs. Kitchen first, then ring Ben." got "I am now at
    the kitchen." and no call at all. Words that claim an action the model never called ask for
    the first thing asked once more, offered only the actions it names; words that claim nothing
    ("I'll wait there.") stay the model's own answer."""
    result, server = await scripted_turn(
        [TextReply("I am now at the kitchen."), call("navigate_to", target="kitchen"),
         call("start_video_call", contact="Ben"), TextReply("Calling Ben.")],
        "Three jobs. Kitchen first, then ring Ben.")
    assert [c.name for c in result.calls] == ["navigate_to", "start_video_call"]
    assert server.requests[1].tool_names == ["navigate_to"]  # offered alone
    result, server = await scripted_turn([TextReply("I'll wait there.")], "Three jobs. Kitchen first, then ring Ben.")
    assert not result.calls and len(server.requests) == 1
    result, server = await scripted_turn(
        [TextReply("I am now at the kitchen."), TextReply("I am in the kitchen now.")],
        "Three jobs. Kitchen first, then ring Ben.")
    assert not result.calls and len(server.requests) == 2  # once only


async def test_words_that_answer_a_request_in_another_language_ask_for_it_once_more() -> None:
    """Text tests v85 and v87: "Zima hiyo projector" got "Zima, hiyo! How can I assist you
    today?" and "Kata simu sasa" nothing done. Said in another language, the model's words are
    no refusal of a request it did not understand: it is asked for once more, in the reading's
    English, offered the actions that English names; in English, words that claim nothing stay."""
    result, server = await scripted_turn(
        [TextReply("Zima, hiyo! How can I assist you today?"), call("set_projector_power", on=False),
         TextReply("The projector is off.")], "Zima hiyo projector, imeniboo.")
    assert [c.name for c in result.calls] == ["set_projector_power"]
    assert server.requests[1].last_user_text == "Now do the next thing I asked: turn off the projector."
    assert server.requests[1].tool_names == ["set_projector_power"]
    result, server = await scripted_turn([TextReply("How can I assist you today?")], "Turn the projector off, love.")
    assert not result.calls and len(server.requests) == 1
    # a request said as a question keeps the model's own answer ("can you turn on the projector?")
    result, server = await scripted_turn([TextReply("Yes, I can switch it on for you.")], "Unaweza kuwasha projector?")
    assert not result.calls and len(server.requests) == 1


async def test_a_turn_ended_with_nothing_to_say_is_asked_for_once_more() -> None:
    """Text test v63: the model read "Kitchen first, and once you're there, switch on the
    projector." back (never spoken) and called nothing. Nothing said and nothing called on a
    request that names a place asks for the first thing once more; on chat it stays an answer."""
    said = "Kitchen first, and once you're there, switch on the projector."
    result, server = await scripted_turn(
        [TextReply(said), call("navigate_to", target="kitchen"), call("set_projector_power", on=True),
         TextReply("The projector is on.")], said)
    assert [c.name for c in result.calls] == ["navigate_to", "set_projector_power"]
    assert server.requests[1].tool_names == ["navigate_to"]
    result, server = await scripted_turn([TextReply("")], "I had a lovely walk this morning.")
    assert not result.calls and len(server.requests) == 1


async def test_after_a_refused_call_in_a_compound_request_the_step_is_offered_what_fits_it() -> None:
    """Dev `wrapup-1` ("Right, wind up the call with Anna and then pop the projector on."): the
    model called Anna, refused as not fitting; offered every tool that fits the request, it did
    the projector and never ended the call. The step is offered what fits *it*."""
    async with scripted_sim(
        [call("start_video_call", contact="Anna"), call("end_video_call"), call("set_projector_power", on=True),
         TextReply("Done.")],
    ) as (robot, server, backend):
        assert robot.sim is not None
        await robot.sim.apply_setup("in_call")
        result = await Assistant(backend, robot.tools).turn(
            "Right, wind up the call with Anna and then pop the projector on.")
        assert robot.sim is not None and robot.sim.state.projector_on
    assert made(result) == [
        ("start_video_call", NOT_REQUESTED), ("end_video_call", None), ("set_projector_power", None)]
    assert sorted(t for t in server.requests[1].tool_names if t in ("end_video_call", "set_projector_power")) == [
        "end_video_call"]
