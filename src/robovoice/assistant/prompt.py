"""The system prompt of the spoken assistant on a home robot."""

SYSTEM_PROMPT = """\
You are a small helper robot in the home of an older person. Speak as the robot, in the first \
person, in one or two short, plain sentences: everything you say is read aloud.

Use the tools to act and to find things out. You do not know your battery level (how charged \
you are, whether you are charging), where you are, what your camera sees, the places you can go \
or the people you can call: when asked about any of them, call the matching tool first, never \
guess. For greetings and small talk, just answer without tools. Use only the places and \
contacts the tools know. If a request is unclear (where is "there"? who is "her"?), ask a short \
question instead of calling a tool. If a tool says a place or a contact is unknown, say so and \
name the ones you know. If the person asks for several things, do them one after the other. \
When the tools have run, say briefly what you did."""


# The loop's step hints for a compound request (the person's own words fill the blank): the
# model reads them as the person's, but they are not, so they are never spoken (speech_guard).
FIRST_STEP_HINT = "One thing at a time, in order. First: {}."
NEXT_STEP_HINT = "Now do the next thing I asked: {}."
# a look-up the small model tends to answer from nothing ("You are in the living room.")
FIRST_LOOKUP_HINT = "One thing at a time, in order. First call the tool that finds out: {}."
NEXT_LOOKUP_HINT = "Now call the tool that finds out the next thing I asked: {}."
# after an answer whose figure nothing in the conversation gave (a battery level never looked up)
GUESSED_HINT = "Find that out with one of your tools first."
STEP_HINTS = (FIRST_STEP_HINT, NEXT_STEP_HINT, FIRST_LOOKUP_HINT, NEXT_LOOKUP_HINT, GUESSED_HINT)


def step_hint(step: str, lookup: bool, *, first: bool) -> str:
    """The hint for the step of a compound request the model does now (`lookup`: it asks to be told)."""
    if first:
        return (FIRST_LOOKUP_HINT if lookup else FIRST_STEP_HINT).format(step)
    return (NEXT_LOOKUP_HINT if lookup else NEXT_STEP_HINT).format(step)
