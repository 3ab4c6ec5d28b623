"""Who a sentence is said to. At home the person often talks to someone else in the room between
requests to the robot ("Robot, ring Clara. Ben, don't you touch that."): a sentence that opens
by calling someone by name, then says something to them, is not for the robot. Read as a step,
the bare "Ben" after a call continued it ("ring Clara … Ben": a second call)."""

from __future__ import annotations

import re

from robovoice.assistant.lexicon import FILLER, IMPERATIVES, QUESTION_WORDS, TAG, fragment

# Sentences; not at a title's full stop ("Dr. Weber").
_SENTENCE = re.compile(r"(?<!\bDr\.)(?<!\bMr\.)(?<!\bMrs\.)(?<!\bMs\.)(?<!\bSt\.)(?<=[.!?])\s+")
# A name said first, with the little words that may come before it ("No, Ben, …", "Sorry, Clara, …").
# (Not after "hey": "Hey Travis, …" is the robot's wake word misheard.)
_CALLED = re.compile(
    r"^(?P<before>(?i:(?:no|oh|ah|sorry|hang on|hold on|wait|look|listen|now|right|ok|okay|well)[\s,!]+)*)"
    r"(?P<name>(?:(?:Dr|Mr|Mrs|Ms|Miss|Doctor|Nurse|Auntie|Aunt|Uncle)\.? )?[A-Za-z][a-z]+)\s*,\s*(?P<rest>\S.*)$")
# Whom the person may talk to beside the robot, by what they call them: said to one of these,
# even a request ("Mum, can you put the kettle on?") is not for the robot.
_FAMILY = frozenset({
    "mum", "mam", "mom", "mummy", "mommy", "mother", "dad", "daddy", "father", "gran", "granny", "grandma",
    "grandmother", "nan", "nana", "nanna", "grandad", "grandpa", "granddad", "grandfather", "son", "daughter",
    "auntie", "aunt", "uncle", "nurse", "doctor",
})
# Capitalised words that open a sentence without naming anyone: greetings, exclamations, the
# robot's own names, what one calls the robot, and the things and places a bare request names.
_NOT_A_PERSON = frozenset({
    "robot", "robbie", "jarvis", "computer", "machine", "hello", "hiya", "howya", "morning", "evening", "afternoon",
    "goodnight", "night", "thanks", "cheers", "ta", "lovely", "great", "good", "fine", "sure", "anyway", "besides",
    "honestly", "seriously", "gosh", "blimey", "crikey", "strewth", "golly", "goodness", "there", "here", "today",
    "tonight", "tomorrow", "later", "quick", "quickly", "again", "yes", "yep", "yup", "yeah", "aye", "no", "nope",
    "nah", "ah", "ahh", "eh", "ooh", "oh", "och", "ach", "whoops", "oops", "sorry", "please", "careful", "easy",
    "gently", "slowly", "remember", "mind", "love", "dear", "darling", "sweetheart", "honey", "pet", "mate", "pal",
    "buddy", "sir", "madam", "lad", "lass", "listen", "look", "oi", "oy", "wait", "hang", "hold", "right", "righto",
    "well", "now", "okay", "ok", "alright", "first", "then", "next", "after", "before", "also", "ugh", "urgh",
    "argh", "brr", "duw", "ha", "hah", "haha", "boy", "wow", "whoa", "woah", "jeez", "gee", "yikes", "cor",
    "crumbs", "heavens", "lord", "lordy", "bless", "phew", "hmm", "hm", "mm", "uh", "um", "er", "erm", "hey", "hi",
    "shh", "shush", "psst", "alas", "ouch", "yay", "hooray", "welp", "meh", "aww", "aw", "viewers", "kitchen",
    "bedroom", "bathroom", "hallway", "hall", "lounge", "living", "front", "door", "dock", "charger", "balcony",
    "garden", "projector", "battery", "camera", "call", "telly", "tv", "lights", "everyone", "everybody", "folks",
    "guys",
})
# What follows a name that is still said to the robot: a list of whom ("Anna, then Ben"), a plea.
_STILL_ASKING = re.compile(r"^(?:then|and|too|as well|please|now|first|next|after)\b", re.IGNORECASE)
# What is said to the person named ("not you", "don't you touch that", "I'll call you back"):
# enough to tell a name from an exclamation the robot does not know.
_TO_THEM = re.compile(r"^(?:(?:not|don'?t|do not) )?you\b|^i(?:'m|'ll|'ve| am| will| was| have)\b", re.IGNORECASE)


def _said_to_someone(sentence: str) -> bool:
    called = _CALLED.match(sentence.strip())
    if called is None:
        return False
    name = called.group("name")
    last = name.split()[-1].lower()
    if last in _NOT_A_PERSON or last in IMPERATIVES or last in QUESTION_WORDS or FILLER.fullmatch(f"{name},") \
            or TAG.match(last):
        return False
    rest = called.group("rest").strip()
    first = re.split(r"[,;:.!?]", rest, maxsplit=1)[0].strip()
    if not first or _STILL_ASKING.match(first) or re.search(r"\bstop\b", rest, re.IGNORECASE):
        return False  # (a spoken stop is always for the robot: it may be what keeps someone safe)
    if _TO_THEM.match(first):
        return name[0].isupper() or last in _FAMILY
    return last in _FAMILY and (first.split()[0].lower() in IMPERATIVES or not fragment(first))


def set_aside(text: str) -> tuple[str, tuple[str, ...]]:
    """`text` without the sentences said to someone else, and those sentences."""
    kept: list[str] = []
    aside: list[str] = []
    for sentence in _SENTENCE.split(text.strip()):
        (aside if _said_to_someone(sentence) else kept).append(sentence)
    return " ".join(kept), tuple(aside)
