"""What the robot could or would do, not what to do now: questions about its abilities, and
requests under a condition ("if Ben rings, …", "… when you're running low", "… in an
emergency"). `intent` reads such clauses as ability questions: nothing acts."""

from __future__ import annotations

import re

from robovoice.assistant.dialects import ROOM
from robovoice.assistant.lexicon import FILLER, IMPERATIVES, NOT_GENERIC, words

_ABILITY = re.compile(
    r"\b(?:are you (?:able|capable)|were you able|is it possible for you|would it be possible|"
    r"would you be able|you (?:would|could|might) be (?:able|capable)|(?:do|would|did) you know how|can robots|"
    r"something you can|the kind of robot|"
    r"how (?:fast|far|well|long) can you|if i (?:asked|needed|wanted)|"
    r"by yourself|on your own|your own way|ever(?! so\b)|"
    r"(?:would|will|can|could|do) you (?:even |actually )?fit)\b"  # "would you fit to go inside there?" (text test v70)
    # surprise or doubt at what it can do: "wait, can you actually project stuff on the wall?"
    r"|^can you (?:actually|really|even|honestly|seriously)\b(?!.*\b(?:please|now|just|for me)\b)"
    # owning a part is asked at the start ("do you have a camera?"); "how much battery do you
    # have left?" asks about the robot's state
    r"|^(?:do you have|have you got)\b"
    # what a part of it can do: "can that projector of yours show films on the wall?" (text test v121)
    r"|^(?!.*\b(?:please|now|for me)\b)(?:can|could|does|will) (?:that|the|this|your) (?:projector|screen|camera)"
    r"(?: of yours)? \w+",
    re.IGNORECASE,
)
# "can you …?" asks about an ability when its object is generic ("a projector", "video calls", "people").
_CAN_GENERIC = re.compile(
    r"^(?:can|could) you \w+(?: \w+)? (?:a|an|people|folks?|anyone|anybody|things|stuff|video calls|calls|projectors)\b"
    r"|^(?:can|could) you \w+ (?:films?|movies?|videos|pictures|photos|music)\b",  # "… show film?" (text test v114)
    re.IGNORECASE,
)
# … unless it names whom or where: "could you make a video call to Ben?", "could you take a
# look in the kitchen?" ask for one now.
_NAMED = re.compile(r"\b(?:to|with) (?:(?:the|my) \w+|Dr\.? [A-Z]|[A-Z][a-z]+)"
                    r"|\b(?:look|peek|peep|gander|glance) (?:at|in|into|round|around) (?:the|my) \w+"
                    # "give Clara a bell", "give her a call"
                    r"|\bgive (?:(?:the|my|our) \w+|Dr\.? [A-Z]\w*|[A-Z][a-z]+|him|her|them|me|us) an? \w+")
# … or a bare plural with no article or owner before it ("can you send text messages?",
# "could you make ordinary phone calls?"), also where or to whom ("can you play films on the
# wall?", "can you make video calls to the doctor?": text test v44, audio test v35): a kind of
# thing, not one the person wants now ("make a video call to the doctor" asks for one).
_CAN_PLURAL = re.compile(r"^(?:can|could) you \w+ ((?:\w+ ){0,2})(\w+s)"
                         r"(?: (?:on|onto|in|around|round|across|to|with) (?:(?:the|a|any|my|our) )?\w+)?$",
                         re.IGNORECASE)


def _asks_about_kinds(text: str) -> bool:
    match = _CAN_PLURAL.match(text.rstrip(" ?.!"))
    return match is not None and not set(words(match.group(1) + match.group(2))) & NOT_GENERIC


# Irish English asks with "would you ever …": "would you ever give Anna a ring there?" is a
# request (every "would you ever" in blind text sets v10-v25 was one, 6 of 6), unless it says
# that it wonders ("would you ever go out on the balcony, do you think?", "… at all?", "… by
# yourself?"); "could you ever …" still asks whether it can
_WOULD_YOU_EVER = re.compile(r"^would you ever (?!.*\b(?:(?:do|d'?) you (?:think|reckon|suppose)|at all|be able|manage"
                             r"|by yourself|on your own|in an emergency)\b)", re.IGNORECASE)


def asks_ever(clause: str, utterance: str) -> bool:
    """A "would you ever …" clause whose sentence, later clauses included, does not say that it
    wonders ("would you ever go down to the kitchen and have a look, love?"): it asks."""
    start = utterance.find(clause)
    sentence = re.split(r"[.?!]", utterance[start:], maxsplit=1)[0] if start >= 0 else clause
    return bool(_WOULD_YOU_EVER.match(FILLER.sub("", sentence.strip())))  # the sentence opens with the clause


def asks_ability(text: str) -> bool:
    """The clause (fillers stripped) asks whether the robot can do something."""
    lowered = text.lower()  # (a "would you ever" that asks is read with its sentence: `asks_ever`)
    return bool(_ABILITY.search(lowered) or (_CAN_GENERIC.search(lowered) and not _NAMED.search(text))
                or _asks_about_kinds(lowered))


# A condition before a request: what to do if or when something happens, not now.
CONDITION = re.compile(  # (not a question: "when will you be charged?"); "supposing I fell, …" too
    # (not "if you could / would / you'd ring Ben for me": a request, said politely)
    rf"^(?:if(?! you(?:'d| could| would) (?:{'|'.join(sorted(IMPERATIVES))})\b)"
    r"|when(?!\s+(?:will|did|do|does|is|are|was|were|can|could|would|shall|have|has)\b)|whenever|in case|"
    r"suppos(?:e|ing)|imagine|what if(?! you\b)|let'?s say|say (?:i|we)\b)\b",  # ("what if you rang Ben?": asked)
    re.IGNORECASE)
# … but a "when" with a verb in the past tells what happened ("when the lights went out I
# thought of Henry, …": text test v45), no condition on what is asked after it
PAST_WHEN = re.compile(r"^when (?:i|he|she|we|they|it|(?:the|my|our|his|her) \w+|(?!(?:is|are|was|were|do|does|did|"
                       r"will|can|could|would|should|shall|has|have|had)\b)[a-z]+) (?:\w+ed|went|was|were|"
                       r"had|did|came|got|fell|rang|broke|left|lost|saw|heard|thought|said|told|knew)\b",
                       re.IGNORECASE)
# … and so is something else happening first, said before anything is asked: "once my
# programme's finished, …", "as soon as Ben's here, …" (not the robot's own step, "once you've
# …"; after a request it is that request's outcome: "call Ben, and once he's on, …")
EVENT_FIRST = re.compile(r"^(?:once|as soon as) (?!(?:you|ye|again|more|upon|that|this|it)\b)"
                         # "after he's had his lunch, …", "after it has lunch, …" (audio test v42)
                         r"|^after (?:he|she|it|they|we|i|his|her|my|our|their)(?:'s| has| have| had| is)?\b"
                         r"(?:(?! you\b).)*\b(?:lunch|dinner|breakfast|tea|supper|nap|rest|bath)\b",
                         re.IGNORECASE)
# A moment to spare: courtesy, never a step to do first ("when you've got a mo, …").
_A_MOMENT = r"(?:a|the) (?:moment|minute|second|sec|mo|chance)\b"
# … but these are courtesy ("if you don't mind, …", "when you're ready, …"), and …
COURTESY = re.compile(
    r"^(?:if|when) (?:you(?:'re| are) (?:ready|free)|you (?:don'?t|do not|wouldn'?t) mind|"
    r"you (?:can|could|would|might|will|please|like|want)\b|you'd (?!(?:been|had|have|gone|seen|done)\b)\w+|"
    r"you(?:'re| are) (?:settled|in position|all set)\b|"
    r"you(?:'d| would) be (?:so |ever so )?(?:kind|good|sweet|a (?:love|dear|darling|star))\b|"
    rf"you(?:'ve| have| get| got)?(?: got)? {_A_MOMENT}|"
    # "if it's not a huge deal, could you …" (text test v69)
    r"it(?:'?s| is) (?:no|not(?: a| too)?)(?: much| huge| big| great)? (?:trouble|bother|deal|problem|hassle)|"
    r"(?:it|that)'?s (?:ok|okay|alright|all right)|possible)",
    re.IGNORECASE)
# … and this is the order of steps, not a condition ("go to the door and when you get there, …").
ON_ARRIVAL = re.compile(r"^(?:when|once) you(?:'re| are)? (?:(?:get|arrive)\w*(?: (?:there|in there|back|in|home))?"
                        r"|there|in there|back|in$)\b[\s,]*", re.IGNORECASE)  # "… when you're in" (text test v51)
# … and so does the outcome of what was asked, after a request ("Go and wait at the front door for
# Clara, and when she's gone come back to the kitchen": text test v133); alone, a condition
_GONE = re.compile(r"^(?:when|once|after) (?:she|he|they)(?:'s| has| have|'ve| is| are)? (?:gone|left)\b[\s,]*",
                   re.IGNORECASE)


def arrived(clause: str, asked: bool) -> re.Match[str] | None:
    """The clause opens on the robot's arrival (`ON_ARRIVAL`), or, where a request was said before
    it (`asked`), on that request's outcome (`_GONE`)."""
    return ON_ARRIVAL.match(clause) or (_GONE.match(clause) if asked else None)


# … these say what to do first ("once you've checked your battery, come here").
# (not "when you have a moment", "when you've got a minute": courtesy)
SEQUENCE = re.compile(r"^(?:only )?(?:once|after|when|as soon as) you(?:'ve| have) "
                      rf"(?!(?:got )?{_A_MOMENT})(\w+)", re.IGNORECASE)
# Being somewhere as the first step: "once you're in the bedroom, …" (not "when you're in the
# kitchen, …": that may be whenever it is), and "… once you've got to the bedroom", said last.
# "…, but only once you're in the kitchen" (text test v93); "… after you reach Abbu in the bedroom" (text test v89)
ONCE_THERE = re.compile(r"^(?:only )?(?:once|as soon as) you(?:(?:'re| are) (?:(?:out|over|up|down|through) )?"  # (v55)
                        r"(?:in|at|by|inside|into)| (?:reach|get (?:to|in|into|inside)|arrive (?:at|in)|make it to)) "
                        r"((?:the|my|your) \w+(?: \w+)?|" + ROOM + r")$"
                        r"|^(?:only )?(?:after|when) you (?:reach|get to|arrive at|make it to)(?: \w+ (?:in|at))?"
                        r" ((?:the|my|your) \w+(?: \w+)?|" + ROOM + r")$",
                        re.IGNORECASE)  # (text test v71: "… after you get to the bedroom")
ARRIVED = re.compile(r"\s+((?:once|when|as soon as) you(?:'re| are) (?:in|at|by|inside) (?:the|my|your) \w+(?: \w+)?"
                     r"|(?:once|when|after|as soon as) you(?:'ve| have) (?:got(?:ten)?|made it|reached|arrived"
                     r"|been|gone|popped|nipped|come|driven|headed|moved)"
                     r"(?: yourself| over| down| up| through| across| back)*"
                     r"(?: (?:to|into|in|at|inside))? (?:the|my|your) \w+(?: \w+)?"
                     # … and said in the present: "call Doctor Weber after you get to the bedroom" (text test v71)
                     # (… or "after you go to the front door", not "when": whenever it goes, text test v99)
                     r"|(?:once|when|after|as soon as) you (?:get|arrive|reach|make it"
                     r"|(?<!when you )(?:go|come|head|drive))"
                     r"(?: back| over| down| up| through)*(?: (?:to|into|in|at)| \w+ (?:in|at))?"
                     r" (?:the|my|your) \w+(?: \w+)?)\s*$",
                     re.IGNORECASE)

# "call Clara after you put the projector on", "go to the kitchen after you've rung Ben" (text
# test v59), in one breath: what comes after "after you" is done first (`SEQUENCE`, `intent`)
AFTER_YOU_DID = re.compile(r"(?<=\w)\s+((?:after|once|as soon as) you(?:'ve| have)? "
                           r"(?!(?:get|go|arrive|are|can|could|do|did|like|want|wish|need|feel|think)\b)\w+ \w.*)$",
                           re.IGNORECASE)
# "Switch the projector off before you head to the bedroom" (text test v26), in one breath:
# what comes after "before you" is the next step ("before you ring Clara, …" said first puts
# the call after what follows: `intent`); two words at least ("… before you forget" asks nothing).
BEFORE_YOU_DO = re.compile(r"(?<=\w)\s+before you\s+(\w+ \w.*)$", re.IGNORECASE)

# A condition after the request ("can you find your way back to your charger when you're running
# low?", "could you ring the doctor in an emergency?"): the same, said the other way round.
_LATE_CONDITION = re.compile(r"\s((?:if|when|whenever|in case)\s.+)$", re.IGNORECASE)
# … but after these, "if" is "whether": "take a picture so I can see if the parcel's there"
# (and after a bare "what", "what if you gave Clara a ring?" is a suggestion: text test v46)
_WHETHER = re.compile(r"\b(?:see|ask|know|check|wonder|tell me|find out|look|sure|^what)"
                      # … with where to look between: "Go see in the bedroom if they there" (text test v126)
                      r"(?:(?<!ask)(?<!know)(?<!sure) (?:in|on|at|by|round|around|inside) (?:the|my|your) \w+"
                      r"(?: room| door)?)?$", re.IGNORECASE)
# … and a "when" after these belongs to what the request is for: "sit in the living room so
# you're ready when I come in" is to be done now (an "if" still puts it off: "ring the doctor so
# I can talk to her if I fall")
_PURPOSE = re.compile(r"\b(?:so(?: that)? (?:you|i|we|he|she|they|it)|in order to|so as to)\b", re.IGNORECASE)
# … and so does one right after "for": "put the projector on for when I get back" is done now
_FOR = re.compile(r"\bfor$", re.IGNORECASE)
_EMERGENCY = re.compile(r"\b(?:in (?:an|case of(?: an)?) emergency|if anything (?:happens|happened|goes wrong))\b",
                        re.IGNORECASE)
# Said beside a "can you …?", these make it a question about ability: "Just out of interest, can
# you …?", "Could you ring the doctor? I just want to know you can."
JUST_ASKING = re.compile(
    r"\b(?:(?:just|only) (?:asking|wondering|curious)|out of (?:interest|curiosity)|hypothetically|in theory|"
    r"in principle|theoretically|technically|"
    r"just so (?:i|we)(?:'m| am| are|'re)? (?:know|clear|sure)|for (?:future|my own|my) (?:reference|information)|"
    r"want(?:ed)? to know (?:(?:if|whether|that) )?you (?:can|could)|"
    # "Can you make video calls to my son, or is that beyond you?": whether it can, said outright
    r"(?:is|would) (?:that|it|this) (?:be )?(?:beyond you|too (?:much|hard|difficult|tricky|complicated) for you)|"
    # "I'm not asking you to do it now, but can you …?": said to be not a request
    r"not (?:asking|telling) you to (?:do (?:it|that|this|anything)|go anywhere)|"
    r"(?:don'?t|do not) (?:need|require) (?:you to do )?(?:it|that|this)(?: done)? (?:now|today|yet|at present|"
    r"at the moment|just now|right now))\b",
    re.IGNORECASE)
QUESTION_FORM = re.compile(r"^(?:can|could|would|will) you\b", re.IGNORECASE)


def asked_as_question(clause: str) -> bool:
    """The clause (fillers aside) is said as a "can / could / would / will you …" question."""
    return bool(QUESTION_FORM.match(FILLER.sub("", clause.strip())))


def conditional(request: str) -> bool:
    """The request (fillers stripped) is to be done only if or when something happens."""
    if _EMERGENCY.search(request):
        return True
    late = _LATE_CONDITION.search(request)
    if late is None or _WHETHER.search(request[:late.start()]):
        return False
    before = request[:late.start()]
    if late.group(1).lower().startswith("when") and (_PURPOSE.search(before) or _FOR.search(before)):
        return False
    return not (COURTESY.match(late.group(1)) or ON_ARRIVAL.match(late.group(1)) or SEQUENCE.match(late.group(1)))
