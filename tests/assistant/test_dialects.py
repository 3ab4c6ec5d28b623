"""Turns of a dialect of English said as standard English says them (assistant/dialects.py)."""

from __future__ import annotations

import pytest

from robovoice.assistant.dialects import as_standard
from robovoice.assistant.intent import read_request


@pytest.mark.parametrize(("said", "english"), [
    ("Off the projector lah, nobody watching.", "Off the projector, nobody watching."),
    ("call the doctor for me can or not?", "can you call the doctor for me?"),
    ("Aiyah... you ring Ben, can anot?", "Aiyah... can you ring Ben?"),
    ("Go toilet see got water on the floor or not", "Go to the toilet see if there is water on the floor"),
    ("Call Ben ah, quickly", "Call Ben, quickly"),
    ("I had a cat", "I had a cat"),  # "ha" and "ah" are particles only at a pause
])
def test_singlish_particles_and_turns_are_said_as_english_says_them(said: str, english: str) -> None:
    assert as_standard(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("Off the projector lah.", ("Off the projector",)),
    ("Aiyah, my back again... call the doctor for me can or not?", ("can you call the doctor for me",)),
    ("You go upstairs can or not?", ()),  # asks what it can do
    ("Maybe better you go and charge, okay?", ("Maybe better you go charge",)),
    ("Better you than me.", ()),
    ("Sorry ha, the hallway quite small, would you fit in there?", ()),  # asks what it can do
    ("Can you fit through the front door, do you reckon?", ()),  # the tag after it asks nothing more
    ("Call Ben ah... wait, no need lah, he's busy.", ()),  # taken back
    ("go to the kitchen— actually nvm, I'll go", ()),
    ("It's okay, you don't have to stop, just carry on.", ()),
    ("Go to the kitchen, wait, no, the bedroom", ("the bedroom",)),
])
def test_a_request_said_in_singlish_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v70: "Off the projector lah, …" and "call the doctor for me can or not?" were
    not requests; "Call Dr. Weber ah... wait, no need lah" called and stopped; "would you fit
    to go inside there?" drove; "you don't have to stop" stopped the drive."""
    assert read_request(text).steps == steps


@pytest.mark.parametrize(("said", "english"), [
    ("Y'all might could call Ben after lunch", "could you call Ben after lunch"),
    ("Okay, might could you roll on to the kitchen?", "Okay, could you roll on to the kitchen?"),
    ("I might could go to the kitchen myself", "I might could go to the kitchen myself"),  # the speaker's plan
    ("quit rollin' and stop actin' up", "quit rolling and stop acting up"),
])
def test_southern_us_turns_are_said_as_english_says_them(said: str, english: str) -> None:
    assert as_standard(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("You might could put the projector on for me, hon.", ("could you put the projector on for me",)),  # "hon": a tag
    ("Holler at Clara for me, would you?", ("Holler at Clara for me",)),
    ("She's all done. Go ahead and hang up the call.", ("hang up the call",)),  # no "go ahead" step
    ("I might could holler at Ben tomorrow.", ()),
])
def test_a_southern_us_request_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v71: "Y'all might could call Doctor Weber after …" and "Holler at Dr. Weber …"
    were talk; "Go ahead and hang up now" made a "Go ahead" step the model took as a drive."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("said", "english"), [
    ("Go a di kitchen, den back a yuh charger.", "Go to the kitchen, then back to your charger."),
    ("Hol' on, nuh go deh, tun roun'.", "hold on, don't go there, turn round."),
    ("Mek we call Anna nuh.", "let's call Anna."),
    ("Put the books in the den, then the kitchen", "Put the books in the den, then the kitchen"),  # a room
    ("Leonardo Di Caprio", "Leonardo Di Caprio"),  # "Di" with a capital may be a name
    ("Open the projector la", "turn on the projector"),
    ("Add oil ar robot! Close projector.", " robot! turn off the projector."),
])
def test_patois_and_hong_kong_turns_are_said_as_english_says_them(said: str, english: str) -> None:
    assert as_standard(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("First go a di kitchen, den call Anna fi mi.", ("First go to the kitchen", "call Anna for me")),
    ("Nuh call Clara yet, she a sleep.", ()),
])
def test_a_patois_or_hong_kong_request_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v72: "go a di kitchen, den call Anna" did only the drive, "mek we call Anna nuh"
    was talk."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("said", "english"), [
    ("Close the light of the projector u go back to charge.", "turn off the projector and go back to charge."),
    ("can u go to the kitchen", "can u go to the kitchen"),  # texting's "you", spelled out later by `lexicon`
    ("Mela, pass from the hallway, then the bedroom, ejja.", "go to the hallway, then the bedroom."),
])
def test_maltese_turns_are_said_as_english_says_them(said: str, english: str) -> None:
    assert as_standard(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("Finish this call, then open the projector, ejja.", ("Finish this call", "turn on the projector")),
    ("Tell me, you drive to the kitchen alone, or someone must push you?", ()),  # asks how, no drive
    ("You go to the kitchen, or call Ben, whichever.", ("You go to the kitchen",)),  # no question: asked
])
def test_a_maltese_request_or_question_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v73: "ejja" was a step, "… u go back to charge" lost the dock, and "you drive to
    the kitchen alone, or someone must push you?" drove."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("said", "english"), [
    ("Switch that projector aff, it's daein' ma heid in.", "Switch that projector off, it's doing' my head in."),
    ("Dinnae go tae the kitchen the noo.", "Don't go to the kitchen now."),
    ("Gonnae no call Ben.", "please don't call Ben."),
    ("Och, gonnae switch the projector aff?", "Och, will you switch the projector off?"),
    ("I'm gonnae phone Anna masel.", "I'm going to phone Anna masel."),  # not asked of the robot
    ("Away ben the kitchen.", "Away through to the kitchen."),  # through: not Ben, the son
    ("I'm no wanting the projector the nicht.", "I'm not wanting the projector tonight."),
    ("Call ma now", "Call ma now"),  # a mother, not "my"
    ("Tell Ben no.", "Tell Ben no."),
])
def test_scots_turns_are_said_as_english_says_them(said: str, english: str) -> None:
    assert as_standard(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("Aye just hang up on Anna there and head back to the dock, so it is.",
     ("Aye just hang up on Anna there", "head back to the dock")),
    ("Dinnae go tae the bathroom the noo, a ghràidh.", ()),
    ("Away ben the bedroom, mo chridhe.", ("Away through to the bedroom",)),
    ("Tapadh leat, that's grand.", ()),
])
def test_a_scots_request_or_talk_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v74: "Aye just hang up …" was talk, so only the drive was done; a Gaelic
    endearment after a request was a second request; "aff" was not "off"."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize("said", ["Get Ben on the screen for me.", "Kitchen, then get Ben.",
                                  "Ah Ma wants to talk to Ben.", "Ben the house is cold."])
def test_english_and_other_dialects_keep_ben_and_ma(said: str) -> None:
    """Scots "ben" (through) and "ma" (my) are lower case: "get Ben" is the son (reading diff)."""
    assert as_standard(said) == said


@pytest.mark.parametrize(("said", "english"), [
    ("Go intae the living room an stick the projector on.", "Go into the living room and stick the projector on."),
    ("an once that's done, an hour later", "and once that's done, an hour later"),  # "an hour" is English
    ("Pit on yon projector, syne hing up.", "put on that projector, then hang up."),
    ("Eh think ye'd better bide here, ken.", "I think you'd better stay here."),
    ("Ah watch the fitba on it.", "I watch the fitba on it."),
    ("Ah, watch out for the step.", "Ah, watch out for the step."),  # English's "Ah, …"
    ("Ken said hello.", "Ken said hello."),  # the name, not the tag
    ("ah'm gonnae need ye tae phone Anna", "I need you to phone Anna"),
    ("Gang by the bedroom, then come back ben the kitchen.",
     "go by the bedroom, then come back through to the kitchen."),
    ("They dug a pit the size of a house.", "They dug a pit the size of a house."),  # a pit
])
def test_more_scots_turns_are_said_as_english_says_them(said: str, english: str) -> None:
    assert as_standard(said) == english


@pytest.mark.parametrize(("text", "steps"), [
    ("Ye'd better pit the projector aff an get yersel tae the kitchen.",
     ("you'd better put the projector off", "get yourself to the kitchen")),
    ("Gang ben the bathroom, syne hing up on Ben.", ("go through to the bathroom", "hang up on Ben")),
    ("Ah like that projector fine, it's braw.", ()),
    ("Haud on, ah'm gonnae need ye in the lobby.", ("I need you in the lobby",)),
])
def test_a_glasgow_request_or_talk_is_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v77: "an" (and) joined two steps into one, "pit", "hing up", "syne" were not
    words the reading knew, and "Ah watch the fitba on it" (I watch) was a request."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Ging ben the hoose tae the kitchie an pit the projector on, min.",
     ("Go through to the house to the kitchen", "put the projector on")),
    ("Ye could watch the news on that projector, it's braw.", ()),
    ("Gyang an see fit she's wintin at the front door.", ("Go see what she's wanting at the front door",)),
    ("You could switch the projector on.", ("You could switch the projector on",)),  # still a request
    ("Will it fit through the door?", ()),  # English "fit"
])
def test_doric_requests_and_what_anyone_could_do_are_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v79: Doric "ging", "the kitchie", "fit she's wintin" were not words the reading
    knew, and "ye could watch the Buddies on it" (anyone could) switched the projector on."""
    assert read_request(text).worded_steps == steps


@pytest.mark.parametrize(("text", "steps"), [
    ("Get thisen to t'kitchen, then switch t'projector on.",
     ("Get yourself to the kitchen", "switch the projector on")),
    ("Ring Clara... nah, scrap it, she'll be asleep by now.", ()),
    ("go to the bathroom... scrap that, i'll go myself", ()),
    ("I don't want owt, thanks.", ()),
    ("Could you take the tray to the kitchen, or you just drive about?", ()),  # asks what it can do (text v83)
])
def test_yorkshire_requests_and_a_scrapped_one_are_read(text: str, steps: tuple[str, ...]) -> None:
    """Text test v82: "go to t'bedroom, then t'bathroom, …" did one step or none ("t'" is "the"),
    and "go to the bathroom... nah scrap that, i'll go myself" drove ("scrap that" took nothing back)."""
    assert read_request(text).worded_steps == steps
