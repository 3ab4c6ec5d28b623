"""Who a sentence is said to. At home the person often talks to someone else in the room between
requests to the robot ("Robot, ring Clara. Ben, don't you touch that."): a sentence that opens
by calling someone by name, then says something to them, is not for the robot. Read as a step,
the bare "Ben" after a call continued it ("ring Clara … Ben": a second call)."""

from __future__ import annotations

import re

from robovoice.assistant.lexicon import (
    FILLER,
    IMPERATIVES,
    QUESTION_WORDS,
    RELATIONS,
    ROBOT_ACTIONS,
    STOP,
    TAG,
    fragment,
)

# Sentences; not at a title's full stop ("Dr. Weber").
_SENTENCE = re.compile(r"(?<!\bDr\.)(?<!\bMr\.)(?<!\bMrs\.)(?<!\bMs\.)(?<!\bSt\.)(?<=[.!?])\s+")
# A name said first, with the little words that may come before it ("No, Ben, …", "Sorry, Clara, …").
# (Not after "hey": "Hey Travis, …" is the robot's wake word misheard.)
_CALLED = re.compile(
    r"^(?P<before>(?i:(?:no|oh|ah|sorry|hang on|hold on|wait|look|listen|now|right|ok|okay|well)[\s,!]+)*)"
    r"(?P<name>(?:(?:Dr|Mr|Mrs|Ms|Miss|Doctor|Nurse|Auntie|Aunt|Uncle)\.? )?[A-Za-z][a-z]+)"
    # "Priya beta, come and eat something" (text test v61): a name with a word of endearment is a person
    r"(?P<dear> (?i:beta|beti|ji|love|dear|darling|pet|sweetheart|hen|bach|cariad|lass|lad|my dear))?"
    r"\s*,\s*(?P<rest>\S.*)$")
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
    "guys", "chalo", "arre", "arey", "acha", "achha", "accha", "haan", "bas", "yaar", "oye", "hai",
})
# What follows a name that is still said to the robot: a list of whom ("Anna, then Ben"), a plea.
_STILL_ASKING = re.compile(r"^(?:then|and|too|as well|please|now|first|next|after|i mean|i meant)\b", re.IGNORECASE)
# What is said to the person named ("not you", "don't you touch that", "I'll call you back"):
# enough to tell a name from an exclamation the robot does not know.
_LISTEN = re.compile(r"^(?:listen|listen up|look here|guess what|you know what)$", re.IGNORECASE)  # said to them
# what one tells a person to do some day, later in the sentence that opens with their name
_YOU_MUST = re.compile(r"^(?:and )?you (?:must|should|have to|'ll have to|will have to|ought to|need to) "
                       r"(?:come|visit|see|pop round|drop by)\b", re.IGNORECASE)
_TO_THEM = re.compile(r"^(?:(?:not|don'?t|do not) )?you\b|^i(?:'m|'ll|'ve| am| will| was| have)\b", re.IGNORECASE)


# The robot called by name ("Robot, …", "And you, robot, …", "…, Jarvis."), not in the wake phrase
# ("Hey Jarvis, …"): a person who turns to the robot this way was talking to someone else before.
_ROBOT_CALLED = re.compile(r"(?<!hey )(?<!hi )(?<!ok )(?<!okay )\b(?:robot|jarvis)\b\s*(?:[,.!?]|$)", re.IGNORECASE)
# A name set off by commas inside or at the end of a sentence: "Sit yourself down, Margaret, …"
_NAME_INSIDE = re.compile(r"(?<=\w),\s+([A-Z][a-z]+)\s*(?:,|[.!?]*$)")
# … but not one that says who a relation is: "ring my son, Ben"
_APPOSITION = re.compile(r"\b(?:" + "|".join(sorted(RELATIONS | {"doctor", "gp", "contact"})) + r"),$", re.IGNORECASE)


def a_person(name: str) -> bool:
    """`name` (said first, or set off by commas) may name a person: capitalised or a family word,
    and no greeting, exclamation, adverb ("Hypothetically, …"), order word or the robot's name."""
    last = name.split()[-1].lower()
    if not (name[0].isupper() or last in _FAMILY) or last.endswith("ly"):
        return False
    return not (last in _NOT_A_PERSON or last in IMPERATIVES or last in QUESTION_WORDS or TAG.match(last)
                or FILLER.fullmatch(f"{name},"))


def _opening_name(sentence: str) -> tuple[re.Match[str], str] | None:
    """The person's name `sentence` opens with (`_CALLED`), and the words up to the next
    punctuation after it; None when it opens with no name."""
    called = _CALLED.match(sentence.strip())
    if called is None or not a_person(called.group("name")):
        return None
    return called, re.split(r"[,;:.!?]", called.group("rest"), maxsplit=1)[0].strip()


def _said_to_someone(sentence: str, robot_called: bool) -> bool:
    """Whether `sentence` is said to someone else; `robot_called`: another sentence calls the
    robot by name, so a name anywhere in this one says whom it is for ("Tom, pop the kettle on"),
    not only a family word or "you" after it."""
    if robot_called and not _ROBOT_CALLED.search(sentence) and not STOP.search(sentence):
        for inside in _NAME_INSIDE.finditer(sentence):
            if a_person(inside.group(1)) and not _APPOSITION.search(sentence[:inside.start() + 1]):
                return True
    if (opening := _opening_name(sentence)) is None:
        return False
    called, first = opening
    name = called.group("name")
    last = name.split()[-1].lower()
    if not first or _STILL_ASKING.match(first) or STOP.search(called.group("rest")):
        return False  # (a spoken stop is always for the robot: it may be what keeps someone safe)
    if _TO_THEM.match(first) or _LISTEN.match(first):  # "Ben, listen, …" (text test v108: during his call)
        return name[0].isupper() or last in _FAMILY
    if name[0].isupper() and any(_YOU_MUST.match(part.strip()) for part in re.split(r"[,;]", called.group("rest"))[1:]):
        return True  # "Ben, the kitchen here has been renovated, you must come and see." (text test v123)
    return (last in _FAMILY or called.group("dear") is not None or (robot_called and name[0].isupper())) and (
        first.split()[0].lower() in IMPERATIVES or not fragment(first))


# "Robot, you ring Anna": after the robot's name, a "you" before a request names who is to do it
# (not in the wake phrase, nor before a verb that also tells how the robot is: "you look tired")
_YOU_DO = re.compile(rf"(?<!hey )(?<!hi )\b((?:robot|jarvis),?\s+)you\s+(?=(?:{ROBOT_ACTIONS})\b)", re.IGNORECASE)


# the speaker turning from someone to the robot inside a sentence: "Hasmukh, wait — no, robot, you go
# to the front door" (text test v132: all of it was set aside as said to Hasmukh)
_TURNS_TO_ROBOT = re.compile(r"(?<=[,\u2014\u2013])\s*(?:(?i:no),?\s+)?(?=(?i:robot|jarvis)\s*,)")


def set_aside(text: str) -> tuple[str, tuple[str, ...]]:
    """`text` without the sentences said to someone else, and those sentences; a request said
    to the robot by name with "you" ("Robot, you ring Anna") as the request it is."""
    sentences = [part for sentence in _SENTENCE.split(_YOU_DO.sub(r"\1", text.strip()))
                 for part in _TURNS_TO_ROBOT.split(sentence) if part.strip()]
    robot_called = any(_ROBOT_CALLED.search(s) for s in sentences)
    kept: list[str] = []
    aside: list[str] = []
    for sentence in sentences:
        if _said_to_someone(sentence, robot_called):
            aside.append(sentence)
        else:
            kept.append(_without_name(sentence) if kept else sentence)
    return " ".join(kept), tuple(aside)


# a person named, then what the speaker wants with them: the name is whom it is about
_ABOUT_THEM = re.compile(r"(?:i|we)(?: really| just)? (?:need|want|would like|'d like|have|wish) to (?:talk|speak|see"
                         r"|call|ring|phone|chat)(?: to| with)? (?:him|her)\b", re.IGNORECASE)


def _without_name(sentence: str) -> str:
    """`sentence` without a person's name it opens with, when a clause of its own follows: said
    after a request, "Ben, stop that!" is a stop, not one more call (to Ben) and a stop."""
    if (opening := _opening_name(sentence)) is None:
        return sentence
    called, first = opening
    if _STILL_ASKING.match(first) or (fragment(first) and first.split()[0].lower() not in IMPERATIVES) \
            or _ABOUT_THEM.match(first):
        return sentence  # "Doctor Weber, I need to talk to him.": whom it is about (text test v115)
    return called.group("before") + called.group("rest")
