"""Reading what the user asked for (`assistant.intent`) and refusing actuation calls nobody
asked for (`assistant.gate`): plain code, made-up utterances, no model."""

from __future__ import annotations

import pytest

from robovoice.assistant.clauses import split_clauses
from robovoice.assistant.gate import NOT_REQUESTED, refusal
from robovoice.assistant.intent import read_request
from robovoice.assistant.reading import ClauseKind
from robovoice.llm.base import ToolSpec

NAV = ToolSpec("navigate_to", "drive")
CALL = ToolSpec("start_video_call", "call")
POSE = ToolSpec("get_robot_pose", "where", read_only=True)


@pytest.mark.parametrize("text", [
    "Bring yourself over to the sofa, please.",
    "Could you pop into the kitchen?",
    "I'd like to speak to my son.",
    "You may hang up now.",
    "Stop!",
    "Why don't you come through to the sofa?",  # a suggestion, whatever its "don't"
    "Don't touch the lamp, but do come here.",
    "Could you make a video call to Ben?",  # names whom: not an ability question
    "Wait for me in the bedroom.",
    "Projector off.",
    "Go to the kitchen with me.",
    "Turn the projector on.",
    "List the places you can drive to.",
    # an imperative's shape around a verb no list has
    "Waddle yourself down to the garden.",
    "Amble across to the sofa, love.",
    "Whack on the projector.",
    # a wish said as what the person wants (eleventh session: tests v13, audio v4)
    "All I want is the projector on.",
    "I'd like the projector switched on, please.",
    "I only want to talk to Dr. Weber.",
    "I just want you in the bedroom.",
    # fifteenth session (text v19): the object before the particle; Irish "would you ever … for me";
    # "for when …" says what it is for, not when
    "Stick the telly on for me, would you?",
    "Would you ever close the curtains for me?",
    "Would you ever drive to the garden, please?",
    "Put the projector on ready for when my sister arrives.",
    # sixteenth session (text v18): advice to the robot asks
    "You ought to close the curtains, it's getting dark.",
    "Perhaps you'd better drive to the garden.",
    "I reckon you should ring the plumber.",
    "Fetch the post for me, if that's okay.",  # courtesy after the comma, not a condition
    "First the garden, then the garage, please.",  # places in order, no verb: the steps
    "The garage first, and then the garden.",
    "Swing by the garage on your way.",  # "swing" is no gerund
    "Away ben tae the garden, would you?",  # Scots: go through to
    # nineteenth session (text v23): "ye", "youse" for you; "y'all" before an imperative
    "Could ye nip out to the garden, pet?",
    "Will youse put the telly on?",
    "Y'all get on over to the garage.",
    # twenty-first session (text v25): Scots "gonnae" (will you), a step said with its "you"
    "Gonnae put the telly on for me?",
    "Firstly you come to the garage.",
])
def test_requests_ask_for_action(text: str) -> None:
    assert read_request(text).asks_action, read_request(text)


@pytest.mark.parametrize(("text", "why"), [
    ("Do not go into the garden.", ClauseKind.NEGATED),
    ("Maybe next week you could call Clara.", ClauseKind.NEGATED),
    ("Keep going, don't stop.", ClauseKind.NEGATED),
    ("Are you able to open doors?", ClauseKind.ABILITY),
    ("Can you call people on the phone if I ask?", ClauseKind.ABILITY),
    ("Anna phoned me on Sunday.", ClauseKind.STATEMENT),
    ("The kitchen floor is wet.", ClauseKind.STATEMENT),
    ("Stay where you are.", ClauseKind.STATEMENT),
    ("Do the lights work in the kitchen?", ClauseKind.QUESTION),
    ("Please, do you know where the kitchen is?", ClauseKind.QUESTION),
    ("Ben went off back to his flat.", ClauseKind.STATEMENT),
    ("Leave the video call alone, I'm still talking to Ben.", ClauseKind.NEGATED),
    ("Just leave the projector be, thanks.", ClauseKind.NEGATED),
    ("Can you drive over to?", ClauseKind.UNFINISHED),  # cut off: the model would pick a place
    ("Please switch the...", ClauseKind.UNFINISHED),
    # calling off asks for nothing new (the loop lets a cancel run while the robot moves)
    ("Never mind, I don't want to go there after all.", ClauseKind.NEGATED),
    ("Never mind about ringing Clara, I'll see her later.", ClauseKind.NEGATED),
    ("Can you send letters, or only pictures?", ClauseKind.ABILITY),  # kinds of thing
    ("Leave the call running.", ClauseKind.NEGATED),
    # the same shape in the past, a gerund, a plural or with a subject is talk
    ("Wandered over to the garden this morning.", ClauseKind.STATEMENT),
    ("Came back to the flat at six.", ClauseKind.STATEMENT),
    ("Lights on the landing are out again.", ClauseKind.STATEMENT),
    ("They moved into the flat upstairs.", ClauseKind.STATEMENT),
    ("I just need a minute to find my glasses.", ClauseKind.STATEMENT),  # no "want": not a wish for the robot
    ("Could you ring the doctor in an emergency? I just want to know you can.", ClauseKind.ABILITY),
    ("Would you ever drive into the garden, at all?", ClauseKind.ABILITY),  # "at all": it wonders
    ("Is the telly on?", ClauseKind.QUESTION),  # an auxiliary is no imperative's verb
    ("Was the heating off all night?", ClauseKind.QUESTION),
    ("Ring the doctor when I fall over.", ClauseKind.ABILITY),  # a condition, not what it is for
    ("You should've rung the plumber yesterday.", ClauseKind.STATEMENT),  # advice too late is talk
    ("You must be worn out from the garden.", ClauseKind.STATEMENT),
    ("My sister says you ought to visit the garden.", ClauseKind.STATEMENT),  # someone else's advice, told
    # a condition after the comma, or a "supposing …" before: what it would do then
    ("Would you phone the plumber, if the pipe burst?", ClauseKind.ABILITY),
    ("Supposing I fell in the garden, would you come out to me?", ClauseKind.ABILITY),
    ("Imagine the lights went out, could you still drive to the garden?", ClauseKind.ABILITY),
    ("Can you fit under the table, do you reckon?", ClauseKind.ABILITY),  # an opinion asked of a "can you"
    ("Just so we know, could you drive into the garden?", ClauseKind.ABILITY),  # said to be only a question
    ("For my own information, can you open the garage?", ClauseKind.ABILITY),
])
def test_no_action_asked(text: str, why: ClauseKind) -> None:
    intent = read_request(text)
    assert not intent.asks_action and intent.refusal is why, intent


def test_compound_requests_keep_their_order_and_verbless_continuations() -> None:
    assert split_clauses("Go to the hall, then switch on the lamp and call Ben.") == [
        "Go to the hall", "switch on the lamp", "call Ben"]
    assert read_request("Drive to the kitchen, then the bedroom, then back to the dock.").steps == (
        "Drive to the kitchen", "the bedroom", "back to the dock")
    assert read_request("Call Dr. Weber, please.").steps == ("Call Dr. Weber",)
    both = read_request("Where are you and how charged are you?")
    assert not both.asks_action and both.steps == ("Where are you", "how charged are you")


def test_go_and_tags_and_elided_continuations_make_no_extra_steps() -> None:
    assert read_request("Go and get your battery charged, dear.").steps == ("Go get your battery charged",)
    assert read_request("Come and sit in the hallway, would you?").steps == ("Come sit in the hallway",)
    assert read_request("Drive to the hall, then on to the bedroom afterwards.").steps == (
        "Drive to the hall", "on to the bedroom afterwards")


def test_a_bare_no_takes_back_what_was_asked_and_a_place_after_it_corrects_it() -> None:
    taken_back = read_request("Turn the projector off. Actually, no, don't bother.")
    assert not taken_back.asks_action and taken_back.refusal is ClauseKind.NEGATED
    corrected = read_request("Drive to the kitchen... no, sorry, the bedroom.")
    assert corrected.steps == ("the bedroom",)
    refused = refusal(corrected, NAV, {"target": "kitchen"})
    assert refused is not None and refused["details"]["reason"] == "negated"
    assert refusal(corrected, NAV, {"target": "bedroom"}) is None
    assert read_request("No, go to the kitchen.").steps == ("go to the kitchen",)  # nothing before to take back


@pytest.mark.parametrize(("text", "steps", "why"), [
    ("If the doorbell goes, would you go to the front door?", (), ClauseKind.ABILITY),  # what it would do then
    ("When Anna calls, switch the projector on.", (), ClauseKind.ABILITY),
    ("When will you be charged?", ("When will you be charged",), ClauseKind.QUESTION),  # a question, not a condition
    ("If you don't mind, come to the hallway.", ("come to the hallway",), None),  # courtesy
    ("When you're ready, call Ben.", ("call Ben",), None),
    ("Once you've checked your battery, drive to the bedroom.",
     ("check your battery", "drive to the bedroom"), None),  # that first, said as a request
    ("It'd be lovely if you could call Clara.", ("It'd be lovely if you could call Clara",), None),  # a wish
    ("I was wondering if you could come to the hallway.", ("I was wondering if you could come to the hallway",), None),
])
def test_conditions_courtesy_and_wishes(text: str, steps: tuple[str, ...], why: ClauseKind | None) -> None:
    intent = read_request(text)
    assert intent.steps == steps and intent.refusal is why, intent


@pytest.mark.parametrize(("text", "steps"), [
    ("Go to the hallway, but first turn the projector on.", ("first turn the projector on", "Go to the hallway")),
    ("Call Ben. Before that, come to the bedroom.", ("come to the bedroom", "Call Ben")),
    ("Before you call Anna, go to the kitchen.", ("go to the kitchen", "call Anna")),
    ("First of all go to the kitchen, then ring Ben.", ("First of all go to the kitchen", "ring Ben")),
    ("Go to the bathroom first, then the hallway.", ("Go to the bathroom first", "the hallway")),  # already in order
    # "once you've <done what was just asked>" only says the order (nineteenth session, text v23)
    ("Halt, and after you've halted drive to the garage.", ("Halt", "drive to the garage")),
])
def test_order_words_put_the_steps_in_the_order_to_do_them(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps", "declined"), [
    # one thing taken back by its name; what was asked beside it stays
    ("Turn the projector on and call Anna - no, not Anna. Just the projector.", ("Turn the projector on",), "anna"),
    ("Call Ben and then drive to the bathroom. Actually, skip the bathroom.", ("Call Ben",), "bathroom"),
    ("Ring Clara and go to the hallway, oh, leave Clara, she's asleep.", ("go to the hallway",), "clara"),
    # keeping a thing as it is asks for nothing
    ("Leave the projector on, please.", (), "projector"),
    ("You can leave the call running.", (), "call"),
    # a dash breaks clauses, and a correction after it stands
    ("Go to the kitchen - no wait, the bedroom.", ("the bedroom",), "kitchen"),
])
def test_taking_back_one_thing_and_keeping_things_as_they_are(text: str, steps: tuple[str, ...], declined: str) -> None:
    intent = read_request(text)
    assert intent.steps == steps and declined in intent.negated_words(), intent


@pytest.mark.parametrize(("text", "carries_on"), [
    ("Keep going, don't stop, I'm talking to the dog.", True),
    ("No need to stop, carry on.", True),
    ("Hold it! Stay put!", False),  # stay put: stop moving
    ("Never mind, don't go there after all.", False),  # calling the drive off
    ("Don't stop at the kitchen, go on to the bedroom.", False),  # a new request
])
def test_words_that_say_carry_on(text: str, carries_on: bool) -> None:
    assert read_request(text).carries_on is carries_on


def test_courtesy_around_a_request_and_an_only_after_step() -> None:
    assert read_request("Be a love and nip to the hallway.").steps == ("nip to the hallway",)
    assert read_request("Could you be an angel and call Ben?").steps == ("Could you call Ben",)
    assert read_request("Switch the projector off, but only after you've gone to the kitchen.").steps == (
        "go to the kitchen", "Switch the projector off")
    assert read_request("Once you've headed to the hallway, ring Ben.").steps == ("head to the hallway", "ring Ben")
    assert read_request("Call Anna. Oh, leave it, she's out.").refusal is ClauseKind.NEGATED


@pytest.mark.parametrize(("text", "steps"), [
    ("Go to the hallway, no, wait a sec, I mean the kitchen.", ("I mean the kitchen",)),
    ("Reckon you could pop to the bedroom, pal?", ("Reckon you could pop to the bedroom",)),
    ("I wondered, if it's no bother, whether you could come to the hallway.",
     ("whether you could come to the hallway",)),
    ("Go to the bedroom and when you get there, turn the projector off.",
     ("Go to the bedroom", "turn the projector off")),  # on arrival: the order, not a condition
    ("Call Anna and go to the kitchen, oh, scrap the kitchen.", ("Call Anna",)),
    ("Head to the door, and when you get there give Ben a ring.", ("Head to the door", "give Ben a ring")),
    ("Go to the kitchen, and once you're in there call Anna.", ("Go to the kitchen", "call Anna")),
    ("Would you pop into the kitchen, no, hang on, not the kitchen, the hallway. The hallway, sorry.",
     ("the hallway",)),  # corrected, and said again: one step
    ("Ring Anna and then go to the kitchen. Actually skip the kitchen, just Anna.", ("Ring Anna",)),
    ("Stop, stop! Go to the bathroom instead.", ("Stop", "Go to the bathroom instead")),
    # a name after a relation says who it is; a request about that person again is the same call
    ("I'd like a word with my son, Ben. Can you get him on the screen?", ("I'd like a word with my son Ben",)),
    ("I want to see Ben, can you call him?", ("I want to see Ben",)),
    # ... but what it is for does not make another request the same one
    ("Ring Clara for me, and then put the projector on so I can see her properly.",
     ("Ring Clara for me", "put the projector on so I can see her properly")),
    # "please do …" asks, though "do" opens questions; a verb no list has, then "off (back) to the"
    ("It's late, no? Please do a call to Anna now.", ("Please do a call to Anna now",)),
    ("Whizz off back to the kitchen, pet.", ("Whizz off back to the kitchen",)),
])
def test_more_everyday_ways_of_asking_and_correcting(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize("text", [
    "Later on, after lunch, you can go back to your charger.",
    "Tomorrow morning, ring Ben.",
    "In a bit, go to the kitchen.",
])
def test_a_clause_that_only_says_when_postpones_what_follows(text: str) -> None:
    assert read_request(text).refusal is ClauseKind.NEGATED


def test_a_time_said_with_more_does_not_postpone_the_next_request() -> None:
    assert read_request("Later is fine for the projector, but go to the kitchen now.").steps == (
        "go to the kitchen now",)


def test_the_doctor_said_before_is_who_him_is() -> None:
    intent = read_request("The doctor rang earlier, can you call him back?")
    assert refusal(intent, CALL, {"contact": "Dr. Weber"}) is None
    refused = refusal(intent, CALL, {"contact": "Anna"})
    assert refused is not None and refused["details"]["reason"] == "unclear"


def test_the_persons_own_plan_after_a_request_is_its_reason() -> None:
    reason = read_request("Give Ben a ring, I want to show him the garden.")
    assert reason.steps == ("Give Ben a ring",)
    assert read_request("Turn the projector on, I'd like to talk to Anna.").steps == (
        "Turn the projector on", "I'd like to talk to Anna")  # asks for a call
    assert read_request("I want to show Ben the garden.").asks_action  # alone, it may be the request


def test_a_tool_named_for_what_was_declined_is_refused() -> None:
    projector = ToolSpec("set_projector_power", "projector")
    declined = read_request("Leave the projector alone, but come here.")
    body = refusal(declined, projector, {"on": False})  # a yes/no argument names nothing
    assert body is not None and body["details"]["reason"] == "negated"
    assert refusal(declined, NAV, {"target": "hallway"}) is None
    assert refusal(read_request("Don't turn the projector off, turn it on."), projector, {"on": True}) is None
    # another value of the same tool, asked by its other name ("my son" is Ben in the description)
    call = ToolSpec("start_video_call", "Call a contact: Anna (daughter), Ben (son), Clara (neighbour).")
    instead = read_request("Don't put Clara on the video, get my son instead.")
    assert refusal(instead, call, {"contact": "Ben"}) is None
    assert refusal(instead, call, {"contact": "Clara"}) is not None
    assert refusal(instead, call, {"contact": "Anna"}) is not None  # nobody asked for the daughter


def test_an_answer_to_the_robots_question_is_a_request() -> None:
    assert not read_request("The bedroom.").asks_action
    assert read_request("The bedroom.", answering=True).asks_action
    assert not read_request("No, not now.", answering=True).asks_action


def test_the_gate_refuses_only_actuation_nobody_asked_for() -> None:
    mention = read_request("My daughter Anna rang yesterday.")
    body = refusal(mention, CALL, {"contact": "Anna"})
    assert body is not None and body["error"] == NOT_REQUESTED and body["details"]["reason"] == "statement"
    assert refusal(mention, POSE, {}) is None  # looking something up is never refused
    assert refusal(read_request("Please call Anna."), CALL, {"contact": "Anna"}) is None
    assert refusal(None, CALL, {"contact": "Anna"}) is None  # audio to an audio model: no words to judge
    either = read_request("Don't call Anna, call Ben instead.")
    assert refusal(either, CALL, {"contact": "Ben"}) is None
    refused = refusal(either, CALL, {"contact": "Anna"})
    assert refused is not None and refused["details"]["reason"] == "negated"
    negated = refusal(read_request("Don't drive to the kitchen."), NAV, {"target": "kitchen"})
    assert negated is not None and "not to do" in negated["hint"]


def test_a_reference_nobody_resolved_is_not_guessed() -> None:
    her = read_request("Call her.")
    body = refusal(her, CALL, {"contact": "Clara"})
    assert body is not None and body["details"]["reason"] == "unclear" and "ask them" in body["hint"]
    assert refusal(her, CALL, {"contact": "Anna"}, said={"anna", "is", "coming"}) is None  # said before
    assert refusal(read_request("I want to see Ben, can you call him?"), CALL, {"contact": "Ben"}) is None
    there = refusal(read_request("Go over there."), NAV, {"target": "kitchen"})
    assert there is not None and there["details"]["reason"] == "unclear"


@pytest.mark.parametrize(("text", "kind"), [
    ("What's your battery level?", ClauseKind.QUESTION),  # a contracted question word is still one
    ("Where's the projector pointing?", ClauseKind.QUESTION),
    ("How much battery do you have left?", ClauseKind.QUESTION),  # the robot's state, not an ability
    ("Do you have a camera?", ClauseKind.ABILITY),
    ("Have you got a way to call people?", ClauseKind.ABILITY),
])
def test_questions_about_state_and_about_abilities(text: str, kind: ClauseKind) -> None:
    assert [c.kind for c in read_request(text).clauses] == [kind]


def test_a_contracted_question_beside_a_request_is_a_step() -> None:
    assert read_request("Go to the kitchen and what's your battery level?").steps == (
        "Go to the kitchen", "what's your battery level")


def test_a_relation_said_before_is_someone_a_reference_can_mean() -> None:
    intent = read_request("My daughter hasn't phoned all week. Get her on the video for me.")
    assert refusal(intent, CALL, {"contact": "Anna"}) is None  # the model looks up who the daughter is
    refused = refusal(read_request("Get her on the video for me."), CALL, {"contact": "Anna"})
    assert refused is not None and refused["details"]["reason"] == "unclear"  # nobody named at all


@pytest.mark.parametrize(("text", "steps"), [
    ("Could you ring Ben if he's not at work?", ()),  # a condition after the request: not now
    ("Can you drive yourself to the dock whenever your battery gets low?", ()),
    ("Would you call my son in an emergency?", ()),
    ("Out of interest, could you switch the projector on?", ()),  # just asking
    ("Could you ring Clara? I only want to know you can.", ()),
    ("Go to the hallway and take a photo so I can see if the post has come.",  # "if" is "whether"
     ("Go to the hallway", "take a photo so I can see if the post has come")),
    ("Call Anna if you don't mind.", ("Call Anna if you don't mind",)),  # courtesy
    ("Where is the charger? Tell me that first, then go to the bedroom.",  # the question is the step
     ("Where is the charger", "go to the bedroom")),
    ("Hallway. Now, please.", ("Hallway",)),  # a bare place, then "now"
    ("Whereabouts are you?", ("Whereabouts are you",)),
    ("Would you know how to phone my daughter?", ()),  # audio test v2 heard this as a request
    ("Once the post has come, you can drive to the study.", ()),  # something else first: not now
    ("Later on, as soon as the rain stops, head to the garden.", ()),
    ("Switch the radio on and once that's done, go to the study.",  # "that": the step before
     ("Switch the radio on", "go to the study")),
    ("Go to the study once more, please.", ("Go to the study once more",)),
])
def test_what_would_be_done_is_not_asked_now(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


def test_a_relation_in_the_possessive_is_someone_too() -> None:
    intent = read_request("It's my son's birthday today, would you ring him for me?")
    assert refusal(intent, CALL, {"contact": "Ben"}) is None


def test_a_possessive_pronoun_names_nobody() -> None:
    """Audio test v2's garbled "could you ring mine?" started a call to Anna."""
    refused = refusal(read_request("Could you ring mine?"), CALL, {"contact": "Anna"})
    assert refused is not None and refused["details"]["reason"] == "unclear"
    assert refusal(read_request("Ring a friend of mine, Clara."), CALL, {"contact": "Clara"}) is None


def test_a_pause_in_a_correction_is_not_a_request_to_wait() -> None:
    """Text test v15: "…, no, wait, the hallway" stopped the robot; the "wait" only holds the correction."""
    intent = read_request("Head over to the kitchen - no, wait, the bedroom.")
    assert intent.steps == ("the bedroom",)
    assert [c.kind for c in intent.clauses if c.text == "wait"] == [ClauseKind.STATEMENT]
    assert read_request("Go to the kitchen. Wait!").steps == ("Go to the kitchen", "Wait")  # no correction: a wait


def test_a_when_in_what_the_request_is_for_does_not_put_it_off() -> None:
    assert read_request("Pop into the bedroom so you're there when Anna rings.").steps == (
        "Pop into the bedroom so you're there when Anna rings",)
    # ... an "if" still does: what to do then, not now
    assert read_request("Could you phone the doctor so I can talk to him if my chest hurts?").asks_action is False


def test_a_colon_before_the_things_asked_splits_them() -> None:
    assert read_request("Two jobs for you: switch the projector on, then drive to the kitchen.").steps == (
        "switch the projector on", "drive to the kitchen")
    # ... and the places listed after an announcement of them are each asked for
    assert read_request("A couple of errands: the kitchen, then the bathroom.").steps == ("the kitchen", "the bathroom")


def test_scratch_that_takes_back_the_request_before_it() -> None:
    """Text test v16: "Call Ben for me. Actually, scratch that, …" made the call ("scratch" read as a verb)."""
    intent = read_request("Ring Clara, please. Actually, scratch that, just drive to the kitchen instead.")
    assert intent.steps == ("just drive to the kitchen instead",)
    assert read_request("Cancel that.").steps == ("Cancel that",)  # nothing before it to take back: a request


def test_i_meant_after_a_no_is_the_correction_and_said_again_is_one_step() -> None:
    assert read_request("Head to the hallway. No, sorry, I meant the bathroom.").steps == ("I meant the bathroom",)
    assert read_request("Go to the kitchen - no, the bedroom, I mean the bedroom.").steps == ("the bedroom",)


def test_before_that_without_its_full_stop_still_puts_what_follows_first() -> None:
    """Audio test v7: the transcript lost the full stop in "go to the bathroom. Before that, …"."""
    assert read_request("drive to the kitchen before that, put the projector on.").steps == (
        "put the projector on", "drive to the kitchen")
    assert read_request("Ring Anna before that show starts.").steps == ("Ring Anna before that show starts",)


def test_a_look_in_a_place_is_asked_of_the_robot() -> None:
    """Dev look-5 (and text test v15's "Have a quick look in the bathroom, then …"): "have"
    opens questions, so the look read as one and the drive there was refused."""
    assert read_request("Take a peek into the hallway, please.").steps == ("Take a peek into the hallway",)
    assert read_request("Have a good look round the kitchen.").asks_action
    # a question, the person's own look, and a look at the robot's own things stay as they were
    assert not read_request("Have you had a look at the kitchen?").asks_action
    assert not read_request("I had a look in the bedroom.").asks_action
    assert not read_request("Have a look through your camera.").asks_action


def test_after_alone_orders_the_steps() -> None:
    """Dev after-1..3 (audio test v7's "go to the living room and after let's go to the kitchen"
    did only the first)."""
    assert read_request("Put the projector on and after ring Clara.").steps == ("Put the projector on", "ring Clara")
    assert read_request("Go to the hall and afterwards, the bedroom.").steps == ("Go to the hall", "the bedroom")
    # "after lunch" is when, not the next step; "after you've …" is what comes first
    assert read_request("Drive to the kitchen and after lunch we could call Ben.").steps == ("Drive to the kitchen",)
    assert read_request("After you've been to the hall, ring Ben.").steps == ("go to the hall", "ring Ben")


def test_a_place_after_a_no_corrects_only_the_last_request() -> None:
    """Dev correct-1 (text test v17: "Turn the projector on, then go to the living room. No,
    sorry, the bedroom." took the projector back too)."""
    assert read_request("Switch the projector off and head to the hall. No, the kitchen.").steps == (
        "Switch the projector off", "the kitchen")
    # the fragments after the corrected request's verb go with it; a bare "no, don't" takes all back
    assert read_request("Call Clara and then Ben. No, just Ben.").steps == ("just Ben",)
    assert read_request("Turn the projector on and go to the hall. No, don't.").steps == ()


def test_saying_it_is_not_asked_now_makes_a_can_you_an_ability_question() -> None:
    """Dev notnow-1, 2 (text test v17: "I'm not asking you to do it now, but can you take
    yourself off to charge …?" docked the robot)."""
    assert not read_request("I'm not asking you to do that, but could you call Anna by yourself?").asks_action
    assert not read_request("I don't need it done yet, but can you drive to the hall alone?").asks_action
    # declining one thing is not saying the next request is only a question
    assert read_request("I don't need you to go to the kitchen, but can you call Ben?").steps == ("can you call Ben",)


def test_a_step_said_with_its_you_is_a_step_and_a_remark_is_not() -> None:
    """Text v25's compound-8 ("First you go to bathroom, after that …") left the drive out."""
    assert read_request("First you switch the telly on, then you go to the garage.").steps == (
        "First you switch the telly on", "you go to the garage")
    assert read_request("Go to the garage, you look worn out.").steps == ("Go to the garage",)
    assert read_request("Then you know the way.").steps == ()


def test_asking_whether_it_is_beyond_the_robot_makes_a_can_you_an_ability_question() -> None:
    """Text v25's ability-2 ("…, or is that beyond you?") started the call."""
    assert not read_request("Could you ring the plumber for me, or would that be too tricky for you?").asks_action
    assert not read_request("Can you drive out to the garden, or is that beyond you?").asks_action
    assert read_request("Gonnae no ring the plumber.").clauses[0].kind is ClauseKind.NEGATED


def test_once_that_is_done_starts_the_next_step() -> None:
    """Dev done-1, done-2 (text v29's "Ring our Ben for me, and once that's done take yourself
    off for a charge." lost the charge); the same words alone ask nothing."""
    assert read_request("Switch the lamp on, and when that's finished head to the garage.").steps == (
        "Switch the lamp on", "head to the garage")
    assert read_request("Ring the plumber, then as soon as that is over go back to bed.").steps == (
        "Ring the plumber", "go back to bed")
    assert read_request("Once that's done, I will have a cup of tea.").steps == ()
    # "after you've done that": the step before, done (not a step "do that" put before it)
    assert read_request("Ring the plumber, and after you've done that go to the garage.").steps == (
        "Ring the plumber", "go to the garage")
    assert read_request("Head to the garage. When you have finished it, come back here.").steps == (
        "Head to the garage", "come back here")


def test_a_goodbye_for_the_person_on_the_call_is_no_step() -> None:
    """Dev farewell-1…3 (text v29's "Tell Anna cheerio and end the call, then come through to
    the kitchen …" spent its steps on the goodbye and never drove); "give … a ring" still asks."""
    assert read_request("Say cheerio to our Sam, hang up, and pop the lamp on.").steps == (
        "hang up", "pop the lamp on")
    assert read_request("Wish Sam goodnight from me, then end the call.").steps == ("end the call",)
    assert not read_request("Say hello to the plumber for me.").asks_action
    assert read_request("Give Sam a ring.").steps == ("Give Sam a ring",)
    assert read_request("Tell Sam to come round.").asks_action


def test_formal_requests_and_capable_questions() -> None:
    """Dev grateful-1, grateful-2, place-1, capable-1, capable-2 (text v30: "I should be most
    grateful if you would place a video call to …" was not read as asked; "… whether you would
    be capable of telephoning my son Ben" started the call)."""
    assert read_request("I should be very thankful if you would ring the plumber.").asks_action
    assert read_request("I'd be ever so glad if you could dim the lamp.").asks_action
    assert read_request("Go to the garage, then place a call to the plumber.").steps == (
        "Go to the garage", "place a call to the plumber")
    assert not read_request("I wonder whether you might be capable of ringing the plumber.").asks_action
    assert not read_request("Could you ring the plumber? I do not require it at the moment.").asks_action
    # "ever so" says how much, not whether ever: a statement, not an ability question
    assert read_request("It's ever so cold in the garage.").clauses[0].kind is ClauseKind.STATEMENT


def test_a_stretched_please_and_once_you_have_got_her_keep_the_request_and_its_order() -> None:
    """Dev stretch-1, stretch-2, gotthem-1, gotthem-2 (text v31: "Pleeease call him" read as no
    request; "Video-chat Clara, and once you've got her, put the projector on …" put the
    projector first)."""
    assert read_request("Pleeease turn the lamp on!").asks_action
    assert read_request("Ring the plumber, and once you've got him, go to the garage.").steps == (
        "Ring the plumber", "go to the garage")
    assert read_request("Go to the garage, and once you have, turn the lamp off.").steps == (
        "Go to the garage", "turn the lamp off")
    assert read_request("Call Sam, but only after you've checked the lamp.").steps == ("check the lamp", "Call Sam")
    assert "1000" in read_request("Drive 1000 metres to the garage.").clauses[0].text  # digits are not stretched


def test_in_principle_or_theoretically_beside_a_can_you_asks_whether_it_can() -> None:
    """Dev principle-1…3 (audio v19's ability-1, "could you in principle make a video call to
    my neighbour?", started the call); the same words in a plain request ask for it."""
    assert not read_request("Can you theoretically ring the plumber?").asks_action
    assert not read_request("In principle, could you drive over to the garage?").asks_action
    assert not read_request("Could you technically dim the lamp by yourself?").asks_action
    assert read_request("Drive to the garage, in principle it's open.").asks_action


def test_a_place_after_not_that_one_replaces_it_and_just_that_is_said_again() -> None:
    """Dev meant-1, meant-2, theory-1 (text test v18: "…, then the kitchen, sorry, not the
    kitchen, I meant the living room" dropped the living room; "what am I saying" became a
    step; "Could you, in theory, show a film …?" switched the projector on)."""
    assert read_request("Go to the hall, then the kitchen, no, not the kitchen, I mean the bedroom.").steps == (
        "Go to the hall", "I mean the bedroom")
    assert read_request("Ring Ben, no, silly me, Clara.").steps == ("Clara",)
    # "just the bedroom" after a withdrawal names what is still asked: not a second step
    assert read_request("Go to the bedroom and put the projector on, well, skip the projector, just the bedroom."
                        ).steps == ("Go to the bedroom",)
    assert not read_request("Would you, hypothetically, drive to the kitchen?").asks_action


def test_a_correction_with_i_mean_is_the_step_and_a_gloss_with_it_is_not() -> None:
    """"…, no, the garden I mean, then …" corrects the place (text v20); "turn it off, the
    projector I mean" only says what "it" was, and pet names ("…, hen") ask nothing."""
    assert read_request("Drive to the garage, no, the garden I mean, then ring Ben.").steps == (
        "the garden I mean", "ring Ben")
    assert read_request("Turn it off, the radio I mean.").steps == ("Turn it off",)
    assert read_request("Away through to the garden for me, hen.").steps == ("Away through to the garden for me",)


def test_a_correction_takes_back_the_last_step_and_a_remark_about_oneself_does_not_end_it() -> None:
    """Dev corr-3…6 (text test v21: "go to the kitchen, then the bedroom, no, sorry, the
    bathroom" took the kitchen back too; "…, no, sorry, I'm muddled, the living room" lost the
    living room)."""
    assert read_request("Wander to the study, then the garage, no, sorry, the garden.").steps == (
        "Wander to the study", "the garden")
    assert read_request("Head to the loft, no, sorry, I'm all at sea today, the cellar.").steps == ("the cellar",)
    assert read_request("Ring Clara, no, my head's all over the place, Ben.").steps == ("Ben",)
    assert read_request("Go to the study, no, I'm fine, thanks.").steps == ()


def test_where_the_robot_will_have_got_to_is_the_first_step() -> None:
    """Dev once-1, 2, 4 (text test v21: "switch the projector on once you've got yourself into
    the living room" and "once you're in the bedroom, get Dr Weber on a video call" did not go)."""
    assert read_request("Ring Clara as soon as you've got to the garden.").steps == (
        "get to the garden", "Ring Clara")
    assert read_request("Once you're in the study, switch the radio off.").steps == (
        "go to the study", "switch the radio off")
    # a drive asked already is not asked twice; a finished job is no place; "when" may be any time
    assert read_request("Head to the study, and once you're in the study, ring Ben.").steps == (
        "Head to the study", "ring Ben")
    assert read_request("Call Ben when you've finished charging.").steps == ("Call Ben when you've finished charging",)
    assert not read_request("When you're in the study, switch the radio off.").asks_action


@pytest.mark.parametrize("text", [
    "Kindly take yourself to the study.",  # Indian English
    "Gie the doctor a ring, would ye?",  # Scots: give; "would ye" is a tag
    "Away ben the study for me.",  # Scots: through to
    "Away you go to the garden, pet.",
    "Kill the radio, would you?",
    "Would you ever pop out to the garden and fetch my hat for me?",  # Irish: "for me" in a later clause
    "Would you ever go out to the garden and then come back to the study.",  # …or a next step
    "Enter the study and wait there.",  # dev enter-1 (audio test v12 heard "head to the front door" so)
])
def test_everyday_requests_from_around_the_isles_and_beyond_ask(text: str) -> None:
    """Dev kindly-1, 2, gie-1, away-2, kill-1, ever-4 (text test v21 read these as talk or as
    questions about ability)."""
    assert read_request(text).asks_action


def test_would_you_ever_asks_unless_it_says_it_wonders() -> None:
    """Every "would you ever" of blind text sets v10-v25 asked (text v25's single-5, "Would you
    ever give our Anna a ring on the video there?", was read as a question)."""
    assert read_request("Would you ever ring the plumber there?").asks_action
    assert not read_request("Would you ever go out to the garden? Just wondering.").asks_action
    assert not read_request("Would you ever go out to the garden, do you reckon?").asks_action
    assert not read_request("Would you ever go out to the garden and look around on your own?").asks_action


@pytest.mark.parametrize("text", ["Ben's bought a boat, would you believe it?", "Can you believe the cheek of him!",
                                  "Clara rang at midnight, can you imagine that?"])
def test_an_exclamation_said_as_a_question_asks_nothing(text: str) -> None:
    """Text test v24 (read run): "…, can you believe it!" after news of Anna started a call."""
    assert not read_request(text).asks_action


def test_once_after_a_request_is_its_outcome_not_something_else_first() -> None:
    """"Call Ben, and once he's on, put the projector on" (an eval text): not put off."""
    steps = read_request("Ring Clara, and once she's on, switch the radio off.").steps
    assert steps[0] == "Ring Clara" and steps[-1] == "switch the radio off"


@pytest.mark.parametrize(("text", "steps"), [
    ("Turn the projector on before you go to the kitchen.", ("Turn the projector on", "go to the kitchen")),
    ("Ring Anna before you head off to your charger, pet.", ("Ring Anna", "head off to your charger")),
    ("Before you call Clara, nip into the hallway.", ("nip into the hallway", "call Clara")),
    ("Ring Ben before you forget.", ("Ring Ben before you forget",)),  # nothing more asked
])
def test_a_request_then_before_you_in_one_breath_is_that_then_the_next(text: str, steps: tuple[str, ...]) -> None:
    """Text test v26: "switch the projector off before you head to the bedroom" was one step."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize("text", ["Go to the bedroom and, uh, then ring Clara, I suppose.",
                                  "Go to the bedroom, uhm, then ring Clara, you know."])
def test_a_hedge_or_an_uh_is_no_step(text: str) -> None:
    """Text test v26: "…, uh, then go wait at the front door for her, I guess" made "uh" and
    "I guess" steps of their own, and the model acted on them."""
    assert [s.lower() for s in read_request(text).steps] == ["go to the bedroom", "ring clara"]


@pytest.mark.parametrize(("text", "steps"), [
    ("Living room, please, love.", ("Living room",)),  # a bare place with a "please" after the comma
    ("Could we have the projector going? It's too dark for the slides.", ("Could we have the projector going",)),
    ("can u ring ben pls", ("can you ring ben please",)),  # texting shorthand
    ("pls go bathroom then charge urself", ("please go to the bathroom", "charge yourself")),
    ("Please to call my daughter Anna, she waits.", ("please call my daughter Anna",)),  # "she waits": no step
    ("Go to the kitchen and then, um, after that, switch the projector on.", ("Go to the kitchen",
                                                                            "switch the projector on")),
    ("Oh and before I forget, could you give Clara a bell?", ("could you give Clara a bell",)),  # names whom
    ("Can you like, go to the bedroom and turn the projector on and stuff?", ("Can you go to the bedroom",
                                                                                     "turn the projector on")),
    ("First, switch on the projector; second, phone Anna.", ("switch on the projector", "phone Anna")),
    ("Hit up Clara on video for me.", ("Hit up Clara on video for me",)),
])
def test_everyday_shorthand_asks_what_it_says(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize("text", [
    "Leave the projector for now, just ring Ben.", "Forget the kitchen, go to the bedroom instead.",
])
def test_leaving_or_forgetting_a_thing_takes_it_back(text: str) -> None:
    assert read_request(text).clauses[0].kind is ClauseKind.NEGATED


def test_forgetting_in_talk_and_a_list_heading_with_please_ask_nothing() -> None:
    assert not read_request("Remind me who I can ring, I always forget the names.").asks_action
    assert read_request("Three things, please: turn the projector on, drive to the kitchen.").steps == (
        "turn the projector on", "drive to the kitchen")


@pytest.mark.parametrize(("text", "steps"), [
    ("yo bot phone clara rn, she's waiting lol", ("yo robot phone clara right now",)),
    ("switch the projector on n go to the kitchen", ("switch the projector on", "go to the kitchen")),
    ("wait, what places do you know? fine, go to the front door after", ("what places do you know",
                                                                         "go to the front door after")),
    ("wait which rooms do you know? go to the hallway after", ("wait which rooms do you know",
                                                                "go to the hallway after")),  # a question
])
def test_texting_words_and_a_wait_before_a_question(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


def test_leave_the_thing_leaves_it_be_and_leave_the_room_goes() -> None:
    assert read_request("Leave it, leave the projector, the baby's asleep.").refusal is ClauseKind.NEGATED
    assert read_request("Leave the kitchen and go to the hallway.").steps == ("Leave the kitchen", "go to the hallway")


def test_an_ability_question_about_stopping_does_not_halt() -> None:
    from robovoice.assistant.halting import halts
    assert not halts(read_request("Hypothetically, if the cat ran in front of you, could you stop in time?"))
    assert halts(read_request("Hold it! Stay put!"))


@pytest.mark.parametrize(("text", "lookups"), [
    ("Check how much battery you've got first, and then head into the kitchen.", (True, False)),
    ("Could you check what your battery's at and then ring Clara?", (True, False)),
    ("See how charged you are first, then go along to the bathroom.", (True, False)),
    ("Check the kitchen and then call Ben.", (False, False)),  # a look in a place is a drive
])
def test_a_check_of_the_robots_own_charge_is_a_look_up(text: str, lookups: tuple[bool, ...]) -> None:
    assert read_request(text).lookups == lookups


def test_see_if_asks_for_a_look_and_after_a_request_says_what_it_is_for() -> None:
    assert read_request("See whether I left the bedroom window open, would you?").asks_action
    assert read_request("Go to the bedroom and see if I left the window open.").steps == ("Go to the bedroom",)
    assert not read_request("See what I mean?").asks_action


@pytest.mark.parametrize(("text", "steps"), [
    ("Right then, bye-bye sweetheart, love to the kids, speak Sunday. You can hang up now, dear.",
     ("You can hang up now",)),
    ("Tell Anna I'm flagging... actually, just end the call.", ("just end the call",)),
    ("Ring Ben and tell him I'll be late.", ("Ring Ben",)),
    ("Give my love to Ben, and hang up.", ("hang up",)),
])
def test_messages_and_partings_for_the_person_on_the_call_are_no_steps(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


def test_a_polite_tell_me_is_a_look_up() -> None:
    assert read_request("Can you tell me what your battery's at, and then take yourself back to the dock?"
                        ).lookups == (True, False)


@pytest.mark.parametrize(("text", "steps"), [
    ("Ring Clara, actually just Ben.", ("just Ben",)),
    ("Go to the kitchen... actually, just ring Ben.", ("just ring Ben",)),
    ("Go to the kitchen. Actually, ring Ben too.", ("Go to the kitchen", "ring Ben too")),
    ("Turn the projector on. Actually, just a sec, ring Ben first.", ("ring Ben first", "Turn the projector on")),
])
def test_actually_just_after_a_request_is_all_that_is_wanted(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Off you go to the bathroom, lad, and then give Clara a ring.",
     ("Off you go to the bathroom", "give Clara a ring")),
    ("Right, off you go to the bedroom, young man.", ("off you go to the bedroom",)),
    ("You can put the phone down on her now, ta.", ("You can put the phone down on her now",)),
    ("Right, off with that projector now, I've seen enough.", ("off with that projector now",)),
    ("Never mind where you were off to. The hallway instead, please.", ("The hallway instead",)),
    ("Hallway, please. Quick as you like.", ("Hallway",)),
])
def test_what_the_robot_is_called_thanks_and_off_with(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "stop"), [
    ("Whoa, whoa, hold still a sec, the cat's right under your wheels!", True),
    ("Oh heavens, keep still, there's a toy on the floor!", True),
    ("Is it possible for you to move around while I'm on a call, or do you have to stay still?", False),
    ("The kids won't keep still.", False),
])
def test_hold_still_said_to_the_robot_is_a_stop(text: str, stop: bool) -> None:
    assert read_request(text).asks_action is stop


def test_a_word_said_again_after_a_hesitation_and_a_name_confirmed_are_one_request() -> None:
    intent = read_request("Put the, um, the picture thing on the wall. The projector, that's it.")
    assert intent.steps == ("Put the picture thing on the wall",)
    assert [c.kind for c in read_request("Go to the, um, the").clauses] == [ClauseKind.UNFINISHED]


@pytest.mark.parametrize(("text", "steps"), [
    ("Switch on the, what's it called, the projector.", ("Switch on the projector",)),
    ("Ring my... you know... my son.", ("Ring my son",)),
    ("Take me to the, oh, the bathroom.", ("Take me to the bathroom",)),
])
def test_a_search_for_the_word_does_not_split_the_request(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "asks"), [
    ("Scrap that, I've changed my mind, the bedroom's where I need you.", True),
    ("The bedroom, that's where I need you.", True),
    ("Kitchen's where you should be, love.", True),
    ("The kitchen is where I want to be.", False),
    ("The living room, that's where my chair is.", False),
])
def test_a_place_where_the_robot_is_wanted_is_asked_for(text: str, asks: bool) -> None:
    assert read_request(text).asks_action is asks


def test_scrap_that_calls_off_and_scratch_that_sofa_does_not() -> None:
    assert [c.kind for c in read_request("Scratch that.").clauses] == [ClauseKind.NEGATED]
    assert not read_request("The cat will scratch that sofa.").asks_action


@pytest.mark.parametrize(("text", "steps"), [
    ("Would you mind switching the projector off and then ringing Clara?",
     ("Would you mind switching the projector off", "ringing Clara")),
    ("I'm going now, love. Could you go to the kitchen and then the hallway to let me out?",
     ("Could you go to the kitchen", "the hallway to let me out")),
    ("My nephew's here. Could you give him a ring later? No, actually, could you give him a ring now?",
     ("could you give him a ring now",)),
])
def test_a_gerund_after_would_you_mind_and_a_place_with_its_purpose_are_steps(
        text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "asks"), [
    ("tbh the projector on this robot is well good", False),  # texting shorthand, no verb "tbh"
    ("The biscuits are in the cupboard, just past the fridge on the right.", False),  # "past" is no verb
    ("hold on can you really throw pictures onto the wall", False),  # surprise: whether it can
    ("Can you really just go to the kitchen now, please?", True),
    ("I'm off now.", False),
    ("Could you give her a call for me?", True),
])
def test_talk_and_surprise_are_not_requests(text: str, asks: bool) -> None:
    assert read_request(text).asks_action is asks


@pytest.mark.parametrize(("text", "steps"), [
    ("Go to the hall... no... no, the bathroom.", ("the bathroom",)),
    ("Call Ben. No, wait, go to the kitchen first.", ("go to the kitchen first", "Call Ben")),
    ("Call Ben. No, wait, go to the kitchen instead.", ("go to the kitchen instead",)),
    ("Bedroom, then the hallway, then back to your charger with you.",
     ("Bedroom", "the hallway", "back to your charger with you")),
])
def test_no_said_twice_first_after_a_no_and_a_list_ending_with_you(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Aw, go on then, pop the projector on for me.", ("pop the projector on for me",)),
    ("Any chance you could nip to the bathroom?", ("Any chance you could nip to the bathroom",)),
    ("Ring my... my daughter, would you?", ("Ring my daughter",)),
    ("Kitchen. Go on.", ("Go on",)),  # after a bare place, "go on" sends the robot off (text test v39)
])
def test_an_urging_go_on_any_chance_and_a_word_said_again_after_a_pause(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize("text", ["Kitchen, slowly.", "Hallway, please, gently.", "Bedroom, nice and quiet now."])
def test_a_bare_place_with_how_to_go_is_asked_for(text: str) -> None:
    assert len(read_request(text).steps) == 1 and read_request(text).asks_action


@pytest.mark.parametrize(("text", "steps"), [
    ("Mum would like you to put the projector on.", ("Mum would like you to put the projector on",)),
    ("Nice and warm in here, isn't it, Jim? Bedroom, please.", ("Bedroom",)),
    ("See me out to the front door, would you?", ("See me out to the front door",)),
    ("Stop, and instead give Anna a ring.", ("Stop", "instead give Anna a ring")),
    ("Jim, tell it. Oh, I'll say it myself. Come to the kitchen.", ("Come to the kitchen",)),
    ("I'll see you later.", ()),  # not "see me out"
    ("Anna always wants you to ring her on Sundays.", ()),  # a habit, not a request passed on
    ("Your dad needs you in the kitchen.", ("Your dad needs you in the kitchen",)),
    ("Kitchen first, then onto the bedroom.", ("Kitchen first", "onto the bedroom")),
])
def test_a_request_passed_on_a_question_tag_see_me_out_and_instead(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "kind"), [
    ("Can you show films on the wall?", ClauseKind.ABILITY),  # a kind of thing, where it would be done
    ("Could you put the film on the wall?", ClauseKind.REQUEST),
    ("Can you make calls to my daughter?", ClauseKind.ABILITY),  # calls: a kind; "a call" asks for one
    ("Can you make a call to my daughter?", ClauseKind.REQUEST),
])
def test_a_bare_plural_with_where_asks_about_a_kind_of_thing(text: str, kind: ClauseKind) -> None:
    assert read_request(text).clauses[0].kind is kind


@pytest.mark.parametrize(("text", "steps"), [
    ("When the heating broke I was frozen, anyway, go to the kitchen.", ("go to the kitchen",)),  # what happened
    ("When Ben rings, go to the kitchen.", ()),  # a condition still
    ("nah, not there. Hallway.", ("Hallway",)),
    ("Item one: 'go to the bedroom'. Item two: 'ring Ben'. OK, do those two.",
     ("first go to the bedroom", "ring Ben")),
])
def test_a_past_when_a_nah_not_there_and_steps_read_out(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Would it be a good idea to put the projector on?", ("Would it be a good idea to put the projector on",)),
    ("Shall we have Clara on the screen?", ("Shall we have Clara on the screen",)),
    ("Shall we go to the kitchen after tea?", ()),  # a suggestion put off
    ("What if you went through to the bedroom?", ("What if you went through to the bedroom",)),
    ("What if I fell, would you ring Ben?", ()),  # a condition still
    ("When you have a moment, go to the hallway.", ("go to the hallway",)),
    ("When you've got a mo, put the projector on.", ("put the projector on",)),
    ("Mm, go to the bedroom, then, like, ring Ben.", ("go to the bedroom", "ring Ben")),
    ("Go to the hallway, where we keep the coats, then come back.", ("Go to the hallway", "come back")),
])
def test_suggestions_courtesy_fillers_and_a_place_described(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("I should like you to go to the bedroom.", ("I should like you to go to the bedroom",)),
    ("Let's see if you can get yourself to the hallway.", ("Let's see if you can get yourself to the hallway",)),
    ("Let's see if you can ring Ben after lunch.", ()),  # put off
    ("Now, first of all, I want you to go to the kitchen.", ("I want you to go to the kitchen",)),
    ("First, the kitchen, then the hallway.", ("the kitchen", "the hallway")),
])
def test_a_teachers_requests_and_first_of_all_alone(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("I don't suppose you could pop to the kitchen?", ("I don't suppose you could pop to the kitchen",)),
    ("I don't suppose it would be too much bother to ring Ben?",
     ("I don't suppose it would be too much bother to ring Ben",)),
    ("I don't suppose you could ring Ben tomorrow?", ()),  # put off
    ("I don't suppose you've seen my glasses?", ()),  # a question, not a request
    ("Maybe it would be kind to ring Clara.", ("Maybe it would be kind to ring Clara",)),
    ("It would be nice to see Anna again.", ()),  # a wish, nobody asked
    ("Steer for the bathroom.", ("Steer for the bathroom",)),
    ("Set a course for the kitchen, then ring Ben.", ("Set a course for the kitchen", "ring Ben")),
    ("Bedroom, smartish.", ("Bedroom",)),
    ("Dad's fine, so stop worrying.", ()),  # a habit given up: no stop of the robot
    ("Stop fussing and go to the kitchen.", ("go to the kitchen",)),
    ("Stop moving!", ("Stop moving",)),  # a stop still
    ("Stop everything.", ("Stop everything",)),
])
def test_suppositions_kindness_steering_and_habits(text: str, steps: tuple[str, ...]) -> None:
    """Text test v48's register: a request said as a supposition or a kindness, a helm order,
    a bare place with "smartish", and "stop worrying" said to somebody."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("You go in the kitchen, I come behind you.", ("You go in the kitchen",)),
    ("Robot, you finish this call now.", ("finish this call now",)),
    ("Make the projector on, and then you call Ben.", ("switch the projector on", "you call Ben")),
    ("You make me laugh.", ()),
    ("You drive like my late husband.", ()),
    ("You always go to the kitchen at night.", ()),
    ("Kindly be going to the bathroom.", ("Kindly be going to the bathroom",)),
    ("Whoa, hold it right there!", ("hold it right there",)),
    ("Please disconnect this call now.", ("Please disconnect this call now",)),
    ("Call Clara, and thereafter go to the front door to receive her.",
     ("Call Clara", "go to the front door to receive her")),
    ("Ring Clara, after you put the projector on.", ("put the projector on", "Ring Clara")),
    ("Ring Ben. I want to talk to him.", ("Ring Ben",)),  # that call again, not a second one
])
def test_requests_in_the_present_tense_and_formal_order_words(text: str, steps: tuple[str, ...]) -> None:
    """Text test v49's register: "you go …" for "go …", "kindly be going", "thereafter"."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Robot, the projector can go off now.", ("the projector can go off now",)),
    ("The projector can go off later.", ()),
    ("Put the projector on, after which come to the bedroom.", ("Put the projector on", "come to the bedroom")),
    ("To the kitchen first, then on to the bathroom.", ("To the kitchen first", "on to the bathroom")),
    ("To the kitchen, that's where she went.", ()),
    ("Projector off, followed by bed for you on the charger.", ("Projector off", "bed for you on the charger")),
    ("Go to the kitchen, and after lunch the bedroom.", ("Go to the kitchen",)),  # after lunch: later
    ("Turn the projector off and straight after go to your dock.", ("Turn the projector off", "go to your dock")),
    ("Go to the kitchen, and straight after lunch ring Ben.", ("Go to the kitchen",)),  # after lunch: later
])
def test_things_that_can_go_off_and_order_words_of_a_list(text: str, steps: tuple[str, ...]) -> None:
    """Text test v50's register: jobs listed in one breath, "after which", "followed by"."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Go to the kitchen and put the projector on when you're in.",
     ("Go to the kitchen", "put the projector on when you're in")),
    ("Put the projector on nice and big, I want to see Anna's photos.", ("Put the projector on nice-and-big",)),
    ("Put the projector on, I want to see Anna.", ("Put the projector on", "I want to see Anna")),  # a call asked
    ("First things first: go to the hallway, then ring Clara.", ("go to the hallway", "ring Clara")),
    ("Ring him, but come into the living room before you do.", ("come into the living room", "Ring him")),
    ("Leave that projector shining where it is.", ()),
    ("Look at it away down the hallway!", ()),  # the robot, talked about
    ("Look at it and tell me what it is.", ("tell me what it is",)),
])
def test_dialect_talk_about_the_robot_and_steps_said_before_you_do(text: str, steps: tuple[str, ...]) -> None:
    """Text test v51's register: "when you're in", "nice and big", "first things first",
    "… before you do", "leave it shining", "look at it away down the hall"."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("After his lunch you can take yourself to the bathroom, but not before.", ()),
    ("After it has lunch, you can take yourself to the bathroom.", ()),  # misheard, still after lunch
    ("Go to the kitchen, but not yet.", ()),
    ("Ring Ben after her lunch.", ()),
    ("Stop stop talking, you can end the call.", ("you can end the call",)),
    ("Stop, stop!", ("Stop",)),
    ("Stop there, then turn round and go back to your dock.", ("Stop there", "go back to your dock")),
])
def test_a_time_held_to_and_a_habit_said_twice(text: str, steps: tuple[str, ...]) -> None:
    """Audio test v42: "after his lunch …, but not before" heard as "after it has lunch, …"
    drove to the bathroom; "that's us done talking" heard as "stop stop talking" stopped the robot."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Go to the bath... no, no. Don't. Stay where you are.", ()),  # no place corrected to
    ("Go to the hallway and back every evening, that's what the nurse said.", ()),  # a habit
    ("Walk to the kitchen and back tomorrow.", ()),  # the time of the whole trip
    ("Walk to the kitchen and back, please.", ("Walk to the kitchen", "back")),
    ("Look at it go! Straight down the hallway.", ()),  # the robot, watched
    ("Look at it go. Now come to the kitchen.", ("Now come to the kitchen",)),
    ("Mum's asking for Clara, if you'd ring her for us.", ("if you'd ring her for us",)),
    ("If you could switch the projector off, that'd be lovely.", ("If you could switch the projector off",)),
    ("If you'd been here you'd have laughed.", ()),
    ("Gran wants that projector off, it hurts her eyes.", ("Gran wants that projector off",)),
    ("She says the kitchen first, then the hallway.", ("She says the kitchen first", "the hallway")),
    ("He says the kitchen is far too cold.", ()),
    ("I reckon it's time you rang Ben.", ("I reckon it's time you rang Ben",)),
    ("It's time for my tablets.", ()),
    ("Hallway. Then give Anna a ring.", ("Hallway", "give Anna a ring")),
    ("Morning! Then ring Anna.", ("ring Anna",)),
    ("Ben phoned, then Clara.", ()),
])
def test_habits_watching_the_robot_and_requests_told_on(text: str, steps: tuple[str, ...]) -> None:
    """Text tests v52 and v53: a doctor's "walk to the front door and back every morning" drove
    there, "Look at him go. Off to the bedroom …" drove, "Stay put" after a "no" stopped the robot;
    "if you'd get her on a video call", "he wants the projector on first", "he says the bathroom
    first" and "it's time we put a call through" were read as talk."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Would it be at all possible to put the projector on?", ("Would it be at all possible to put the projector on",)),
    ("I'd be so grateful if you'd ring Clara.", ("I'd be so grateful if you'd ring Clara",)),
    ("I was hoping you'd switch the projector off.", ("I was hoping you'd switch the projector off",)),
    ("The bathroom, if you would.", ("The bathroom",)),
    ("Reroute: the kitchen.", ("the kitchen",)),
    ("ping Anna on the video", ("ping Anna on the video",)),
    ("Drop the call, thanks.", ("Drop the call",)),
    ("Scrap that trip.", ()),  # a call-off: the cancel runs while the robot moves (halting.halts)
    ("Ring Ben... ah no, forget I asked, he's at work.", ()),
    ("Go to the kitchen, ah no, the front door.", ("the front door",)),
])
def test_polite_indirect_requests_and_a_gadgets_words(text: str, steps: tuple[str, ...]) -> None:
    """Text test v54: "would it be at all possible to …", "I'd be ever so grateful if you'd …",
    "I was hoping you'd …", "the hallway, if you would", "Reroute: front door", "ping Ben",
    "drop the call" were read as talk or as ability questions, "scrap that route" cancelled
    nothing, and "ah no, sorry, forget I said that" took back nothing (the drive ran)."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Living room, quick smart, please.", ("Living room",)),
    ("The kitchen, robot, chop chop.", ("The kitchen",)),  # the robot's name between: no word of the request
    ("Off to bed with you now.", ("Off to bed with you now",)),
    ("Mum went off to bed early.", ()),
    ("Put the projector on, and when it's ready ring Clara.", ("Put the projector on", "ring Clara")),
    ("Once you're over in the bedroom, put the projector on.", ("go to the bedroom", "put the projector on")),
    ("Switch the projector off, but pop into the kitchen before that.",
     ("pop into the kitchen", "Switch the projector off")),
    ("Ring Anna. Before that, go to the kitchen.", ("go to the kitchen", "Ring Anna")),
    ("Swing by the front door, would ya?", ("Swing by the front door",)),  # "ya": you; a tag, no step
    ("Call Clara after you've come to the hallway and turned the projector off.",
     ("come to the hallway", "turn the projector off", "Call Clara")),  # two things done first (text v54)
    ("Crank up that projector, would you?", ("Crank up that projector",)),  # (text v56)
    ("Ring Clara, but before that switch the projector off.", ("switch the projector off", "Ring Clara")),
    ("Go to the hallway and then I wanna ring Anna.", ("Go to the hallway", "I want to ring Anna")),
    ("I need to be sure she's in, so ring Clara for me.", ("so ring Clara for me",)),  # why, said first
    ("Turn the projector on, I want to see the football.", ("Turn the projector on",)),  # a look, no call
    ("Put the projector on, I want to see Anna.", ("Put the projector on", "I want to see Anna")),  # a call
    ("Put the projector on once you're in the living room.", ("go to the living room", "Put the projector on")),
    ("I almost told you to stop, but carry on, it's fine.", ()),  # (text v57)
    ("I'm telling you to stop!", ("I'm telling you to stop",)),
])
def test_a_casual_register_haste_and_a_late_before_that(text: str, steps: tuple[str, ...]) -> None:
    """Text test v55: "Bathroom, quick smart.", "Front door, Jarvis, chop chop.", "Off to bed with
    ya", "once it's warmed up call Anna", "once you're out in the hallway, …" and "…, but go to the
    living room before that" were talk, a lost step or a step out of order."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("There she goes, off to the kitchen again.", ()),  # watched, not asked
    ("And off he goes, down the hallway like a tank.", ()),
    ("There he goes. Bedroom, please.", ("Bedroom",)),  # a bare place with "please" is still asked
    ("I'll put the kettle on and sit in the living room for a bit.", ()),  # the speaker's own plan
    ("I'm going to ring the chemist and then pop to the front door.", ()),
    ("I'll wait here and call Anna for me.", ("call Anna for me",)),  # "for me": asked of the robot
    ("I'll put the kettle on, and you go to the kitchen.", ("you go to the kitchen",)),
    ("Can you video call the surgery, or only Dr. Weber?", ()),  # what it can do
    ("Call Ben, or just Anna if he's busy.", ("Call Ben",)),
    ("Ring Clara, and when you're done with that go back to your charger.",
     ("Ring Clara", "go back to your charger")),
    ("Ring Clara, and after you've done that, go into the bedroom.", ("Ring Clara", "go into the bedroom")),
    ("Mrs Pritchard asked me to get you to call Clara.", ("call Clara",)),  # passed on through the speaker
    ("Dr. Weber wants me to have you switch the projector off.", ("switch the projector off",)),
    ("Anna told me to ask you to ring her tomorrow.", ()),  # passed on, for later
    ("Nobody asked me to get you to call Clara.", ()),
    ("Ring Dr Weber this afternoon.", ()),  # later today, not now
    ("Turn the front door, just so you know.", ()),  # news ("…, just so you know"), audio test v49's mishearing
    ("Go to the kitchen. Just so you know, Ben is coming.", ("Go to the kitchen",)),
])
def test_watched_own_plans_scope_questions_and_passed_on_requests(text: str, steps: tuple[str, ...]) -> None:
    """Text test v58: "There he goes, off to the bathroom again" and "I'll pop the milk in the fridge
    and leave the spare key by the front door" drove; "Can you video call the surgery itself, or
    only Dr. Weber?" called; "…, and when you're done with that get yourself back on the charger"
    lost two steps; "X asked me to get you to call Clara" asked nothing."""
    assert read_request(text).steps == steps



@pytest.mark.parametrize(("text", "steps"), [
    ("Go on so, ring Anna for me.", ("ring Anna for me",)),  # the urging is no step
    ("call Clara after u put the projector on", ("put the projector on", "call Clara")),  # one breath, done first
    ("go to the kitchen after you've rung Ben. ty", ("ring Ben", "go to the kitchen")),
    ("Head to the bedroom once you've phoned Clara.", ("phone Clara", "Head to the bedroom")),
    ("Don't call Clara after you put the projector on.", ()),
    ("I'll ring you after you've charged.", ()),
    ("vid call Anna pls", ("video call Anna please",)),
    ("once ur in the kitchen video call Clara", ("go to the kitchen", "video call Clara")),  # no comma
    ("Once you're in the living room put the projector on.", ("go to the living room", "put the projector on")),
    ("once you're in the kitchen I'll be happy", ()),
    ("wait no keep going, I don't want u to stop", ()),  # a stop not wanted
    ("Call Ben. Before that, the kitchen.", ("the kitchen", "Call Ben")),  # the place after "before that"
    ("Go to the front door, and once you're done there come back and wait in the hallway.",
     ("Go to the front door", "come back wait in the hallway")),  # where to wait is where to go
])
def test_one_breath_orders_texting_and_a_stop_not_wanted(text: str, steps: tuple[str, ...]) -> None:
    """Text tests v59 and v60: "call Clara after u put the projector on", "… after you've rung Ben",
    "once ur in the kitchen video call Clara" lost a step or its order; "I don't want u to stop"
    cancelled the drive; "… come back and wait in the hallway" ran the robot's stop."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Chalo, the kitchen smells lovely. Priya beta, come and eat something.", ()),  # said to a person
    ("Tom love, go and put the kettle on.", ()),
    ("Jarvis love, go to the kitchen.", ("go to the kitchen",)),  # the robot's own name
    ("Ji, tell it to go to the bedroom, no? My shawl is there.", ("go to the bedroom",)),  # relayed; a tag
    ("Don't tell it to go to the kitchen.", ()),
    ("Change of plan, not the kitchen. Living room, and ring Clara.", ("Living room", "ring Clara")),
    ("Not the kitchen. Bathroom.", ("Bathroom",)),
])
def test_endearments_relays_by_someone_in_the_room_and_the_place_after_not_that(
        text: str, steps: tuple[str, ...]) -> None:
    """Text test v61: "Priya beta, come and eat something …" drove to the kitchen; "tell it to go to
    the bedroom, no?" was withdrawn by its tag; "not the kitchen. Living room, and ring Clara …"
    lost the drive."""
    assert read_request(text).steps == steps


def test_away_and_is_go_and() -> None:
    """Old text v51, in the final read run: "…, away and wait by the front door for her" ran the
    robot's stop ("wait"); "away and" is Scots for "go and". "far away and …" is no request."""
    assert read_request("That's Clara, away and wait by the front door for her.").steps == (
        "go wait by the front door for her",)
    assert read_request("I live far away and rarely ring Anna.").steps == ()


def test_once_youve_hung_up_is_the_end_of_the_call_first() -> None:
    """Text test v62: "Once you've hung up with Anna, flick the projector on …" lost the end of
    the call ("hung" had no base form)."""
    assert read_request("Once you've hung up with Ben, head into the kitchen.").steps == (
        "hang up with Ben", "head into the kitchen")


@pytest.mark.parametrize(("text", "steps"), [
    ("Pop over to the hallway, but not right now, love.", ()),  # a time that is not now, after it
    ("Ring Clara for me. Not at the moment though, she's at the shops.", ()),
    ("Later on, after lunch perhaps, I'd like you to go to the bedroom.", ()),  # a hedged time carries on
    ("Perhaps, go to the kitchen.", ("go to the kitchen",)),  # a hedge alone puts nothing off
    ("Stop, not now!", ("Stop",)),  # a spoken stop stays a stop
    ("Kitchen, real quick, the kettle's whistling.", ("Kitchen",)),  # haste after a bare place
    ("I'd very much like to speak to Ben, if you'd be good enough to ring him.",
     ("I'd very much like to speak to Ben",)),
    ("Turn the projector off, then I wonder if you'd be good enough to pop into the kitchen.",
     ("Turn the projector off", "I wonder if you'd pop into the kitchen")),  # no "please"
    ("Give Ben a ring, and when that's done, put the projector on.", ("Give Ben a ring", "put the projector on")),
    ("When you're done, call Ben.", ()),  # said first: something under way, a condition
    ("Bedroom, after that the bathroom.", ("Bedroom", "the bathroom")),  # a route of bare places
    ("Hallway, then the kitchen, and then off to your charger with you.",
     ("Hallway", "the kitchen", "off to your charger with you")),
    ("Hang up on Ben, then it's straight back to your charger for you.",
     ("Hang up on Ben", "it's straight back to your charger for you")),
    ("Put the projector off, then it's back to bed for me.", ("Put the projector off",)),  # the speaker's
    ("Belay that order. Drop the trip, we're staying put.", ()),  # a call-off: the cancel's, if driving
    ("Scrub that errand and douse the projector, please.", ("douse the projector",)),
])
def test_times_not_now_after_a_request_routes_of_bare_places_and_call_offs(text: str, steps: tuple[str, ...]) -> None:
    """Text test v63: "…, but not at the moment, thank you" drove; "bathroom, real quick, …",
    "front door, after that the kitchen", "Bathroom, then the bedroom, and then home to the dock
    with you", "I'd very much like to speak to … Ben, if you'd be good enough to …", "…, and when
    that's done, make your way along to the bedroom?", "…, then it's back to your berth for a
    charge", "Belay that. Abandon the trip" and "Scrub that run, and douse the projector" lost steps."""
    assert read_request(text).steps == steps


def test_a_call_off_in_a_sailors_words_lets_the_cancel_run_and_kind_enough_does_not() -> None:
    from robovoice.assistant.halting import halts
    assert halts(read_request("Belay that. Abandon the trip, we're not going anywhere."))
    assert halts(read_request("Drop the trip, we're staying put."))
    assert not halts(read_request("Drop the call."))
    assert not halts(read_request("Scrub the floor for me."))


@pytest.mark.parametrize(("text", "steps"), [
    ("Give Clara a ring. Hang on. Hallway first, the signal's better there.", ("Hallway first", "Give Clara a ring")),
    ("Switch the projector off, then bedroom first.", ("bedroom first", "Switch the projector off")),
    ("Kitchen first, then ring Ben.", ("Kitchen first", "ring Ben")),  # first already
    ("Right, enough for now. Switch the projector off.", ("Switch the projector off",)),  # no step of its own
    ("Turn the projector on, and once it's up and going ring Anna.", ("Turn the projector on", "ring Anna")),
    ("Bathroom, and then give Ben a bell.", ("Bathroom", "give Ben a bell")),
])
def test_a_place_put_first_after_a_pause_enough_for_now_and_once_its_up(text: str, steps: tuple[str, ...]) -> None:
    """Text test v64: "Turn the projector on. Wait. Living room first, …" did the projector first;
    "Okay, enough now. End the call and …" made "enough now" the first step (the model said it
    back and did nothing); "…, and once it's up give Clara a ring …" lost the call."""
    assert read_request(text).steps == steps


def test_enough_alone_still_halts_a_drive() -> None:
    from robovoice.assistant.halting import halts
    assert halts(read_request("Enough now!"))


def test_names_in_a_row_with_no_verb_are_a_list_not_calls() -> None:
    """Audio test v55: "go to the living room and then call Anna" was heard "… and Ben, Clara, Anna."
    and Ben was called. Names in a row with only commas between them are no steps."""
    assert read_request("go to the living room and Ben, Clara, Anna.").steps == ("go to the living room",)
    assert read_request("Call Ben, then Clara.").steps == ("Call Ben", "Clara")


@pytest.mark.parametrize(("text", "steps"), [
    ("Abeg call Ben, I dey for kitchen.", ("Abeg call Ben",)),  # Pidgin "please"
    ("Ring Clara. No, I beg your pardon, I mean Anna.", ("I mean Anna",)),
    ("Off the projector and go to the bedroom.", ("Off the projector", "go to the bedroom")),
    ("Go living room, then on the projector for the children.",
     ("Go to the living room", "on the projector for the children")),
    ("I'd like to know if you're able to go and charge without being reminded.", ()),  # what it can do
    ("I'd like to know where you are.", ("I'd like to know where you are",)),  # a look-up asked for
])
def test_pidgin_courtesy_a_formal_pardon_on_and_off_as_verbs_and_wanting_to_know(
        text: str, steps: tuple[str, ...]) -> None:
    """Text test v65: "Abeg ring Anna …", "No, I beg your pardon, I mean the bathroom", "…, on the
    projector so …" and "Off the projector, then go charge" lost their steps; "I should like to
    know whether you are capable of taking yourself off to be charged …" drove to the dock."""
    assert read_request(text).steps == steps
    if "pardon" in text:
        assert read_request(text).worded_steps == ("Ring Anna",)


@pytest.mark.parametrize(("text", "steps"), [
    ("Through to the kitchen, love.", ("Through to the kitchen",)),  # a way, a word for the robot after it
    ("Into the bedroom, he went.", ()),  # told, not asked
    ("Kitchen. Then call Clara. Over and out.", ("Kitchen", "call Clara")),  # a sign-off is no step
    ("Pop into the living room, and once you've spotted her ring Clara.", ("Pop into the living room", "ring Clara")),
    ("Message for Kirsty: the bathroom tap drips, give it a tighten.", ()),  # a note for somebody else
    ("Note for you: go to the kitchen.", ("go to the kitchen",)),
])
def test_a_way_with_a_vocative_a_sign_off_once_youve_found_him_and_a_note_for_someone(
        text: str, steps: tuple[str, ...]) -> None:
    """Text test v66: "Into the bedroom, mate." asked nothing; "Stop. Back to dock. Call Ben. Out."
    ended the call; "…, and once you've found him ring his girl Anna" put "find him" first; "Note
    for Dad: front door sticks in the heat, give it a shove." drove to the front door."""
    assert read_request(text).steps == steps


def test_a_noun_in_a_requests_shape_with_a_verb_of_telling_after_it_is_talk() -> None:
    """Audio test v57: "Merv's kitchen on the farm had a wood stove" heard "first kitchen on the
    farm had a wood stove." drove to the kitchen: "kitchen on the" had the shape of "switch on
    the"."""
    assert read_request("you know, first kitchen on the farm had a wood stove.").steps == ()
    assert read_request("Flick on the telly.").steps == ("Flick on the telly",)


@pytest.mark.parametrize(("text", "steps"), [
    ("Ask the robot not to go into the bathroom, the tiles are slippery.", ()),  # passed on: not wanted
    ("Tell it to go to the bedroom.", ("go to the bedroom",)),
    ("Right, cut the call please, we're done.", ("cut the call please",)),
    ("I would request you to go to the bedroom.", ("I would request you to go to the bedroom",)),
    ("Change of plan: the bathroom instead.", ("the bathroom instead",)),
    ("Once you reach the bedroom, switch the projector on.", ("go to the bedroom", "switch the projector on")),
    ("Projector chalu kar do, please.", ("turn on the Projector",)),
    ("Arre, please projector bandh kar do.", ("please turn off the projector",)),
    ("Can you make the projector brighter, or does it only go on and off?", ()),
    ("dude head to the kitchen", ("dude head to the kitchen",)),
])
def test_passed_on_not_to_cut_i_request_a_new_plan_once_you_reach_hindi_switches_and_on_and_off(
        text: str, steps: tuple[str, ...]) -> None:
    """Text test v68: "Tell the machine not to go in the kitchen, …" drove; "Tell the machine to
    cut the call now", "I would request you to move to the hallway", "ok new plan, living room
    instead", "Projector band karo, …", "Once you reach the front door, tell it to call Anna" and
    "bro go charge" lost steps; "could you like dim the projector, or is it just on and off?"
    switched it off."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("After you switch the projector off head to the bedroom.", ("switch the projector off", "head to the bedroom")),
    ("before you call Ben go to the kitchen", ("go to the kitchen", "call Ben")),
    ("Before ringing the doctor, go to the bedroom.", ("go to the bedroom", "ring the doctor")),  # (audio v59)
    ("before going to bed I read a book", ()),  # somebody else doing it
    ("Before charging, switch the projector off.", ("switch the projector off",)),  # no thing it is done to
    ("After you've been to the garage come back into the lounge.", ("go to the garage", "come back into the lounge")),
])
def test_an_order_words_clause_run_into_the_command_without_a_comma(text: str, steps: tuple[str, ...]) -> None:
    """Audio test v58: "before you call Clara switch on the projector." (heard with no comma) was
    one request, and the call was never made."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("The projector off now, thanks.", ("The projector off now",)),
    ("Please the projector off now.", ("Please the projector off now",)),
    ("the telly's off now", ()),  # told, not asked
    ("Ben is off now", ()),
])
def test_a_terse_command_with_now_after_it(text: str, steps: tuple[str, ...]) -> None:
    """Found while writing a dev case: "Please the projector off now." was talk, "The projector
    off, please." a request."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Okay, hang up and then, um, I guess head back to the dock.", ("hang up", "I guess head back to the dock")),
    ("I suppose switch the projector off, then.", ("I suppose switch the projector off",)),
    ("Maybe go to the kitchen.", ("Maybe go to the kitchen",)),
    ("I guess so.", ()),
    ("I think Ben will call later.", ()),
    ("If it's not a huge deal, could you head over to the front door?", ("could you head over to the front door",)),
    ("If it's no big deal, could you go to the kitchen?", ("could you go to the kitchen",)),
    ("Oy vey, the bedroom, please.", ("the bedroom",)),
])
def test_a_hedged_command_and_a_courtesy_condition(text: str, steps: tuple[str, ...]) -> None:
    """Text test v69: "…, um, I guess head back to the dock and charge?" lost the drive, and
    "if it's not a huge deal, could you maybe head over to the front door?" was read as a
    question about ability, so nothing ran."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Okay, I think we can end the call now.", ("I think we can end the call now",)),
    ("I reckon we might as well hang up now.", ("I reckon we might as well hang up now",)),
    ("We should call Anna more often.", ()),  # no "now": the person's own thought
    ("We could have called Ben now.", ()),
    ("We can call Ben tomorrow.", ()),
])
def test_we_can_do_it_now_asks(text: str, steps: tuple[str, ...]) -> None:
    """Audio test v60: "okay, I think we can end the call now" was talk, and the call went on."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Could you call Doctor Weber after you get to the bedroom.", ("go to the bedroom", "Could you call Doctor Weber")),
    ("Put the projector on when you get to the bedroom.", ("go to the bedroom", "Put the projector on")),
    ("Ring Clara once you reach the living room, please.", ("go to the living room", "Ring Clara")),
])
def test_an_arrival_said_in_the_present_after_the_request_is_done_first(text: str, steps: tuple[str, ...]) -> None:
    """Text test v71: "… call Doctor Weber after you get to the bedroom" was one step, and the model
    only called; "once you've got to …" was read so already."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # a place more for the drive said first comes before the call held back (text test v82)
    ("Before you call my nephew Ben, please go to the front door, and after that to the living room.",
     ("please go to the front door", "to the living room", "call my nephew Ben")),
    # a request of its own after it comes after the call, as before (text tests v67, v71)
    ("Before you ring Ben, turn that projector off, hey, and afterwards you can go and charge.",
     ("turn that projector off", "ring Ben", "you can go charge")),
    ("Before you call Ben, get yourself into the kitchen, and once you've rung him, back to your charger you go.",
     ("get yourself into the kitchen", "call Ben", "go back to your charger")),
    # courtesy around a request, and "fire … up" (text test v82)
    ("Please be so kind as to come to the living room, I am sitting here only.", ("Please come to the living room",)),
    ("Get thisen to t'living room and fire t'projector up, t'match is on.",
     ("Get yourself to the living room", "fire the projector up")),
])
def test_before_you_holds_the_call_back_and_courtesy_is_read(text: str, steps: tuple[str, ...]) -> None:
    assert tuple(read_request(text).worded_steps) == steps


@pytest.mark.parametrize(("text", "steps"), [
    # a bare "no, wait" and then "before that": a step put first, the one taken back kept (text v91)
    ("Turn the projector off. No, wait, before that, go to the living room.",
     ("go to the living room", "Turn the projector off")),
    ("Ring Anna, oh wait, no, go to the bedroom first.", ("go to the bedroom first", "Ring Anna")),
    # "no, forget it" takes it back for good, whatever comes after
    ("Call Clara. No, forget it. Before that I'd better have my lunch.", ()),
    ("Ring Anna, no, forget it, go to the bedroom first.", ("go to the bedroom first",)),
    # "from there": the next step (text v90)
    ("Head to the bedroom, and from there go on to the bathroom.", ("Head to the bedroom", "go on to the bathroom")),
    ("From there you can see the garden.", ()),
])
def test_no_wait_before_that_keeps_the_step_and_from_there_is_the_next(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # "…, but only once you're in X" after a request: being there first; its "not before" says it again (text v93)
    ("Ring Anna, but only once you're in the bedroom.", ("go to the bedroom", "Ring Anna")),
    ("Switch the projector on, only when you get to the living room, not before.",
     ("go to the living room", "Switch the projector on")),
    # … but a request after it is what it leads to
    ("Go to the bedroom, and once you're in the bedroom, ring Ben.", ("Go to the bedroom", "ring Ben")),
    # "after you reach <someone> in X" (text v89)
    ("Give Ben a ring after you reach Mum in the kitchen.", ("go to the kitchen", "Give Ben a ring")),
    # a drive that names a person: not the call again (text v92)
    ("Hang up on Ben, dear, and go let him in at the front door.",
     ("Hang up on Ben", "go let him in at the front door")),
    # "leave us to it": why it goes; it takes nothing back (text v92)
    ("Call Clara and then pop off to the bedroom and leave us to it.", ("Call Clara", "pop off to the bedroom")),
    ("Ring Clara, no, leave Clara, go to the kitchen.", ("go to the kitchen",)),
    # "before you ring him": the call said already; "before all of that": first of all (text v90)
    ("Ring Dr. Weber, but before you ring him, switch the projector off, and before all of that, go to the bedroom.",
     ("go to the bedroom", "switch the projector off", "Ring Dr. Weber")),
])
def test_there_first_when_said_after_a_call_said_again_and_before_all_that(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # "um" heard as "I'm" before a bare verb (audio v83); "I'm going to …", "I'm off to …" are the speaker's own
    ("I'm Chuck the projector on for us, love.", ("I'm Chuck the projector on for us",)),
    ("I'm going to ring Ben later.", ()),
    ("I'm off to the kitchen.", ()),
    # "be a <anything> and …": courtesy around the request, with a "go and" after it (audio v84)
    ("Be a champ and go and call Ben.", ("go call Ben",)),
])
def test_a_misheard_um_and_be_a_anything_and(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # "once you've talked to her": the call said before, then the next step (text v94)
    ("Ring Anna, and once you've talked to her, go back to your charger.", ("Ring Anna", "go back to your charger")),
    # how to walk, said to a person, is no step (text v94: it drove to the bathroom named before it)
    ("Careful, the hallway is slippery, Grandpa, walk slowly now.", ()),
    ("Go slowly to the kitchen.", ("Go slowly to the kitchen",)),
    # "before you rings Ben" (text v95)
    ("Before you rings Ben, come into the living room.", ("come into the living room", "ring Ben")),
    # "but first X" after a request, and "… before all of that" ending a clause: first (text v95)
    ("Ring Clara, but first the hallway, and turn the projector off before all of that.",
     ("turn the projector off before all of that", "first the hallway", "Ring Clara")),
    ("First the kitchen, then the bedroom.", ("First the kitchen", "the bedroom")),
    # "First thing,": an order word, no step (text v95)
    ("First thing, go to the bathroom, then call Dr. Weber.", ("go to the bathroom", "call Dr. Weber")),
])
def test_talked_to_her_manner_only_rings_but_first_and_first_thing(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # words in no Latin letters are read as talk, not a crash (text v98's Ukrainian "please" raised IndexError)
    ("Будь ласка, go to the front door, somebody ring the bell.", ("go to the front door",)),
    ("Будь ласка.", ()),
    ("你好, call Anna.", ("call Anna",)),
])
def test_words_in_another_script_are_talk(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # "no hang on" takes back, and "not yet" after a pause still holds the request back (audio v88: it drove)
    ("Go to the kitchen, no hang on, not yet, after lunch.", ()),
    ("Go to the kitchen, hang on, not yet.", ()),
    ("Go to the kitchen, no hang on, the bedroom.", ("the bedroom",)),
    # Caribbean English: "…, nah" a softener, "leh we", "de", "carry yuhself", "yuh could …?" (text v96)
    ("Go in de bedroom an' check de window, nah.", ("Go in the bedroom", "check de window")),
    ("Leh we ring Clara, but before dat, tun off de projector.", ("turn off the projector", "let's ring Clara")),
    ("Yuh could ring people abroad, or is only family?", ()),
    ("Go to the kitchen? Nah.", ()),
    # an ability question's fragments go on asking it (text v97: "The doctor and that?" rang him)
    ("Can you do the video calls? With the family? Ben and that?", ()),
])
def test_a_pause_before_not_yet_caribbean_turns_and_an_ability_questions_fragments(
        text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # English as a second language (text v98): please in Polish, "like it is", "not necessary", no article,
    # "in the end" before the last step
    ("Bathroom, proszę bardzo.", ("Bathroom",)),
    ("Leave light of projector like it is, don't turn off.", ()),
    ("Ring Ben? No, not necessary, he visits tomorrow.", ()),
    ("Wait in kitchen for me, I come soon.", ("Wait in kitchen for me",)),
    ("First go to bathroom, then kitchen, and in the end back to your charger.",
     ("First go to bathroom", "kitchen", "in the end back to your charger")),
])
def test_english_as_a_second_language(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # Mandarin and Cantonese courtesy inside English (text v99)
    ("Qing come to the living room, I want to show you something.", ("please come to the living room",)),
    ("Mh goi, the projector close la, too bright.", ("turn off the projector", "too bright")),
    ("Xiexie, robot, very good.", ()),
    ("Ring Anna after you go to the kitchen, hao ma?", ("go to the kitchen", "Ring Anna")),
    ("Is the projector close to the wall?", ("Is the projector close to the wall",)),  # a question, no switch
])
def test_mandarin_and_cantonese_courtesy(text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Turn the project or off and ring Clara.", ("Turn the projector off", "ring Clara")),
    ("Switch on the project or head to the lounge.", ("Switch on the projector", "head to the lounge")),
    ("Is it a project or a hobby?", ("Is it a project or a hobby",)),  # no projector misheard
    ("End the coil now, Martha.", ("End the call now",)),  # (audio tests v102, v103)
    ("The coil in the garden hose is stuck.", ()),
])
def test_the_project_or_is_the_projector_misheard(text: str, steps: tuple[str, ...]) -> None:
    """Audio test v104: "Switch off the project or go to the bathroom, then call Anna." was read as
    one thing or the other, and the drive was never made; a "coil" ended is the call."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    # text test v121: a question announced, a part's ability asked, a call talked of with "is"
    ("Tell me one thing, can that projector of yours show films on the wall?", ()),
    ("Can your camera see into the kitchen?", ()),
    ("Video call is only for Anna, or Ben also you can reach?", ()),
    ("Call Anna, is she up?", ("Call Anna", "is she up")),  # the request before the question stays
    ("Then sit on your charger.", ("sit on your charger",)),
])
def test_a_question_announced_a_parts_ability_and_a_call_talked_of_ask_nothing(
        text: str, steps: tuple[str, ...]) -> None:
    assert read_request(text).steps == steps


def test_a_room_to_come_back_to_is_worded_as_a_drive_there() -> None:
    """Told "come back to the living room", the model went to the dock (text test v121)."""
    intent = read_request("After you check the front door, come back to the living room, okay?")
    assert intent.worded_steps == ("check the front door", "go to the living room")
    assert read_request("Come back to your dock.").worded_steps == ("Come back to your dock",)


@pytest.mark.parametrize(("said", "steps"), [
    # text test v126-v128: an ellipsis character ends a clause; "see … if" is whether; a carer
    # passes on a wish; the robot watched is no request; "forget that" with its comma lost
    ("I'm so tired\u2026 take me to the bedroom.", ("take me to the bedroom",)),
    ("Go look in the hallway if the door is shut.", ("Go look in the hallway if the door is shut",)),
    ("She'd like you to ring Ben.", ("She'd like you to ring Ben",)),
    ("He'd like the projector turned off.", ("He'd like the projector turned off",)),
    ("Look at the robot going into the kitchen by itself.", ()),
    ("Go to the front door, forget that I'll get it myself.", ()),
    # text test v129-v131: a carry-on said with "you"; "let it go"; an "or no?" tag asks; an
    # attention-getter; "I'm wanting to"; "but first A and B"; a wait after a request; "maybe you …?"
    ("Don't you stop now, you're doing fine.", ()),
    ("Let it go, don't stop.", ()),
    ("You can play films on the wall, or no?", ()),
    ("Can you ring folk on the telly?", ()),
    ("Listen carefully. Go to the kitchen.", ("Go to the kitchen",)),
    ("I'm wanting to talk to Anna.", ("I'm wanting to talk to Anna",)),
    ("Ring Ben, but first come to the bedroom and switch the projector off.",
     ("first come to the bedroom", "switch the projector off", "Ring Ben")),
    ("Go to the kitchen and wait a bit; after that, the hallway.", ("Go to the kitchen", "the hallway")),
    ("Maybe you pop over to the hallway?", ("Maybe you pop over to the hallway",)),
    ("Switch off the projector also.", ("Switch off the projector also",)),
])
def test_fiftieth_session_readings(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


@pytest.mark.parametrize(("said", "steps"), [
    # text test v133 (grandchildren): a drive said in play; a request passed on; a request's outcome
    ("You are a rocket and your base is the kitchen, so fly there now!", ("so fly there now",)),
    ("Nana says ring Clara.", ("Nana says ring Clara",)),
    ("Go and wait by the front door for Ben, and when he's gone come back to the hallway.",
     ("Go wait by the front door for Ben", "come back to the hallway")),
    ("When he's gone, ring Anna.", ()),  # alone, a condition
    # text test v134: carrying on, with the place the person thinks it is going to
    ("No, don't stop, keep going to the bedroom.", ()),
])
def test_fiftieth_session_readings_round_three(said: str, steps: tuple[str, ...]) -> None:
    assert read_request(said).steps == steps


@pytest.mark.parametrize("said", [
    "Go to the kitchen after my puja.",  # audio test v123, "after my future" as heard: put off
    "Switch the projector on after her prayers.",
])
def test_after_something_of_the_persons_said_last_puts_the_request_off(said: str) -> None:
    assert read_request(said).steps == ()


def test_once_the_projector_is_on_is_the_switch_then_what_follows() -> None:
    """Text test v134: "Once the projector's on, ring Anna …" is a state only the robot brings about."""
    assert read_request("As soon as the projector is on, video call Ben for me.").steps == (
        "switch the projector on", "video call Ben for me")
    assert read_request("Once the projector's on, I'll call Anna.").steps == ()  # what the person will do


def test_a_question_word_passes_no_request_on() -> None:
    """"Grandpa says call …" passes a request on (text test v133); "Who says call Ben?" asks who."""
    assert read_request("Grandpa says call Ben.").asks_action
    assert not read_request("Who says call Ben?").asks_action
