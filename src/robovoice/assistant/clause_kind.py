"""What kind of clause one clause is, on its own: a request, a negated or postponed one, an
ability question, a question about the robot's state or a statement. Plain code, no model.

`intent.read_request` reads the clauses of an utterance together (order words, corrections,
conditions); this is the first look at each one alone.
"""

from __future__ import annotations

import re

from robovoice.assistant.hypothetical import asks_ability
from robovoice.assistant.lexicon import (
    DO_THOSE,
    FILLER,
    HABIT,
    HASTE,
    IMPERATIVE_SHAPE,
    IMPERATIVES,
    IN_ORDER,
    LATER,
    NOT_A_VERB,
    QUESTION_WORDS,
    RHETORICAL,
    ROBOT_ACTIONS,
    STOP,
    WANTED_THERE,
    YOU_DO,
    words,
)
from robovoice.assistant.reading import ClauseKind

_NEGATION = re.compile(
    r"\b(?:don'?t|do not|doesn'?t|does not|didn'?t|did not|never|no need|not necessary|not now|not yet|not right now|"
    r"not just now|not today|not before|not until|let'?s not|shouldn'?t|should not|mustn'?t|must not|"
    r"hold off|rather not|rather you didn'?t|no,|gonnae no|"
    r"leave (?:\w+ ){1,3}(?:alone|be|(?:as|like) (?:it|they) (?:is|are)|where (?:it|they) (?:is|are)|running|going|"
    r"shining|"
    r"burning|glowing|on|off|in peace|for now|for the moment"
    r"|for the time being)|^forget (?:about )?(?:the|my|your|going|calling|ringing|phoning)\b|"
    r"let (?:it|that|them) be|don'?t touch)\b"
    r"|\bnot\s*$|^not\b"  # "…, not Ben"
    # "leave it, leave the projector": as it is (not "leave the kitchen": go out of it)
    r"|^leave (?:the|my|your|that) (?!(?:\w+ )?(?:room|kitchen|hall|hallway|house|flat|lounge|garden)$)\w+(?: \w+)?$",
    re.IGNORECASE,
)
_MIND = re.compile(r"\bif you (?:don'?t|do not|wouldn'?t|would not) mind\b")  # courtesy, not a "don't"
# someone named by a plain word, who passes a request on ("Harold wants you to …", "Grandpa says call …");
# not the speaker, the robot, a thing, or a question word ("Who says call Ben?" asks)
_SOMEONE = r"(?!i\b|we\b|you\b|it\b|that\b|this\b|what\b|who\b|nobody\b|no one\b)[a-z]+"
_POLITE = re.compile(
    r"^(?:can|could|would|will|won'?t) you\b|^would you mind\b|^why don'?t you\b|^how about\b|^let'?s\b|"
    r"^gonnae\b(?! no\b)|^time to\b|^(?:off|away) you go\b|^go and\b|^(?:could|can|may) we (?:have|get)\b|"
    # advice to the robot is a request, not a past it missed ("you ought to charge up", "I think
    # you'd better ring Clara"; not "you should have seen it", "you must be tired"), nor what anyone
    # could do ("ye could watch the Buddies on it", text test v79)
    r"^(?:(?:i think|i reckon|i'd say|maybe|perhaps|probably) )?you(?:'d| had)? (?:can|could|may|should|need to|"
    r"must|ought to|better|might want to)\b"
    r"(?!'ve\b| (?:have|be|been)\b| (?:even |just )?(?:watch|enjoy|listen|hear|read)\b)|"
    r"^(?:(?:i think|maybe|perhaps|probably) )?(?:better|best) you (?!than\b)\w+|"  # Singlish advice (text test v70)
    # "I think we can end the call now" (audio test v60; not "we should call Ben more often")
    r"^(?:(?:i think|i guess|i reckon|maybe) )?we (?:can|could|may as well|might as well) (?!have\b|be\b|not\b)\w+"
    r"\b.*\bnow$|"
    r"^i(?:'d| would| should) (?:(?:very much|really|so much) )?like (?:you|to|the|my|a|an|some|it)\b"
    r"|^i(?:'d| would) (?:really )?love\b|"  # "I'd very much like to speak to my nephew Ben" (text test v63)
    r"^i(?:'d| would)? (?:kindly )?request you to\b|"  # "I would request you to move to …" (text test v68)
    # (not what someone else is to do: "I want Anna to see the garden", text test v34)
    r"^i (?:really )?(?:want|need|wish)\b(?! (?:(?:my|our) \w+|(?!you\b|it\b|this\b|that\b|the\b|a\b|an\b"
    r"|to\b)\w+) to \w)|"
    r"^i (?:only|just|really) want (?:you\b|to (?!know\b|ask\b|check\b|hear\b))|"
    # "I'm wanting to speak to Doctor Weber" (Scots, Irish and Indian English: text test v130)
    r"^i(?:'m| am) (?:really |just )?(?:wanting|needing) (?:you\b|to (?!know\b|ask\b|check\b|hear\b))|"
    r"^(?:all|what|the one thing) i(?:'d| would)? (?:really )?(?:want|need|like) (?:from you )?is\b|"
    # wishes addressed to the robot: "it'd be lovely if you could…", "I wonder if you could…"
    r"^it(?:'d| would)? be (?:\w+ )?(?:lovely|nice|great|good|helpful|wonderful|kind|grand) if you\b|"
    r"^i(?:'m| am| was)? wonder(?:ing|ed)? (?:if|whether) you\b|^do you think you could\b|^if you (?:could|would)\b|"
    r"^i(?:'m| am| was)? hoping (?:that )?you(?:'d| would| could| might| can| will)\b|"  # (text test v54)
    # "…, if you'd get her on a video call for him" (text test v53); not "if you'd been / gone / seen …"
    r"^if you'd (?!(?:been|had|gone|seen|done|got|told|said|left|made|taken|heard|known|\w+ed)\b)\w+|"
    r"^(?:i |do you )?reckon you (?:could|can|might)\b|^whether you (?:could|might|would|can)\b|"
    r"^i(?:'d| would| should) (?:be (?:\w+ ){0,2}(?:grateful|obliged|thankful|glad)|appreciate it) if you\b|"
    # the most formal: "might you …", "may I ask you to …", "would it be too much trouble to …"
    r"^(?:would )?you(?:'d| would)? be (?:so |ever so )?(?:kind|good) (?:enough (?:as )?|as )to\b|"
    # a request passed on for somebody in the room: "Harold wants you to put the projector on",
    # "she wants you in the bedroom" (text test v44, audio test v35)
    r"^(?:" + _SOMEONE + r"|(?:my|your|our) \w+)"
    r"(?: (?:wants|needs|would like)|'d like) you "
    r"(?:to\b|(?:in|at|by) the\b)|"
    # … or the thing as they want it: "he wants the projector on first" (text test v53)
    r"^(?:" + _SOMEONE + r"|(?:my|our) \w+)"
    r"(?: (?:wants|needs|would like)|'d like) "
    r"(?:the|that|his|her|your) \w+ (?:(?:switched|turned|put) )?"  # "He'd like the projector switched off" (v128)
    r"(?:on|off)\b|"
    # … or the place first, told on for someone: "he says the bathroom first, then …" (text test v53)
    r"^(?:(?!i\b|we\b|you\b|it\b|nobody\b|no one\b)[a-z]+|(?:my|our) \w+) (?:says|said|wants) "
    r"(?:the|my|your) \w+(?: \w+)? (?:first|next|now|please)$|"
    # … or the request itself, passed on: "Grandpa says call Doctor Weber" (text test v133)
    r"^(?:" + _SOMEONE + r"|(?:my|our) \w+) says,? (?:please )?"
    r"(?:call|ring|phone|go|come|switch|turn|put|hang up|end)\b|"
    # "I think it's time we put a call through to Dr. Weber" (text test v52); not "it's time for lunch"
    r"^(?:(?:so|well|and) )?(?:(?:i think|i reckon|i'd say) )?it'?s (?:about |high )?time (?:we|you) (?!were\b)\w+|"
    # "…, then it's back to your berth for a charge" (text test v63); not "it's back to bed for me"
    r"^it'?s (?:straight )?(?:back|off|home) (?:to|into|onto|on to) (?:your\b|(?:the|your) [\w ]+ (?:for|with) you\b)|"
    r"^might you\b|^(?:is there )?any chance (?:you(?:'d| could| would| can| might| will)?|of you)\b|"
    r"^(?:may|might|can|could) i (?:(?:ask|trouble|bother) you (?:to|for)|"
    r"(?:get|have) you to (?!myself|me\b)\w+)\b"
    # "maybe you drive over to the bathroom?": a suggestion (text test v131)
    r"|^(?:perhaps|maybe) you (?:just )?(?:go|drive|come|head|pop|nip|call|ring|phone|switch|turn|put|end|hang)\b"
    r"|^(?:perhaps|maybe) you might\b"
    r"(?! have| be| been)|^would it be (?:\w+ ){0,2}(?:inconvenient|trouble|bother|ok|okay|alright|all right|possible)"
    r"(?: (?:for you )?to| if you)\b|"
    # "would it be an idea to ring Anna?", "it might be a good idea to …", "shall we have the
    # projector on?", "what if you gave Clara a ring?" (text test v46; "… after tea" is put off)
    r"^shall we\b|^what if you\b|"
    r"^(?:would|might|could) it (?:not )?be (?:a good |an )idea to\b"
    r"|^(?:(?:perhaps|maybe) )?it(?:'d| would| might)? be (?:a good idea|an idea|kind|best|wise|sensible|"
    r"(?:nice|good|lovely|helpful) of you) to\b",  # "perhaps it would be kind to ring her" (text test v48)
    re.IGNORECASE)

# Calling off what was asked ("never mind", "forget it") asks for nothing new: while the robot
# moves, the loop lets its stop and cancel tools run anyway (voice roles "stop", "cancel").
_CALL_OFF = re.compile(r"\b(?:never ?mind|after all|forget (?:it|that|about)|call it off)\b|^leave (?:it|that)$"
                       r"|^let (?:it|that) go$"  # "Arey, let it go, don't stop, …" (text test v129)
                       r"|^(?:scrap|scratch|ignore|disregard|belay|scrub|abandon|abort|drop) (?:it|that|this|the)"
                       # "Belay that.", "Abandon the trip", "Scrub that run" (text test v63)
                       r"(?: (?:route|trip|drive|journey|plan|idea|order|one|run|errand|outing))?$"
                       # "forget I said that", "forget what I asked" (text test v54: the drive went ahead)
                       r"|\bforget (?:(?:that )?i (?:said|asked)|what i (?:said|asked))\b",
                       re.IGNORECASE)
# A suggestion is a request, whatever its "don't": "why don't you come through?", "why not pop in?"
_SUGGEST = re.compile(r"^(?:why (?:don'?t|not)|how about|what about)\b"
                      # "I don't suppose you could …", "… it would be too much bother to …" (text test v48)
                      r"|^i don'?t (?:suppose|s'pose) (?:you (?:could|would|might|can)|it(?:'d| would) be "
                      r"(?:too much |any )?(?:trouble|bother))\b", re.IGNORECASE)
_CHALLENGE = re.compile(r"^let'?s see (?:if|whether) you can\b", re.IGNORECASE)
# "see if the bedroom light's on", "see how charged you are": a look asked for (after a request, what
# it is for: "go to the bedroom and see if I left the window open", read_request)
SEE_IF = re.compile(r"^see (?:if|whether|how (?:much|many|full|charged|far|long)|what (?:your|the))\b", re.IGNORECASE)
# "have a look in the bathroom": asked of the robot, though "have" opens questions ("have you …?")
_LOOK = re.compile(r"^(?:have|take) a (?:quick |little |good |proper )?(?:look|peek|peep|gander)"
                   r" (?:in|into|inside|at|round|around|on|over) (?:the|my|our)\b"
                   r"|" + SEE_IF.pattern, re.IGNORECASE)
# "look how beautiful the projector makes the room": an exclamation, no look asked (text test v116)
_LOOK_HOW = re.compile(r"^look (?:how|what)\b|^look at (?:that|this|those|these|them|him|her|it)\W*$"
                       # "Look the little robot la going down the hallway" (text test v126): the robot watched
                       r"|^(?:look|watch)(?: at)? (?:(?:the|that|this|my) (?:\w+ )?(?:robot|machine|thing)"
                       r"|it|him|you|that|this)"
                       r"(?: \w+)? (?:\w+ing|go)\b", re.IGNORECASE)
# "See me to the front door", "see us out": a request to go along (not "see you later")
_SEE_OFF = re.compile(r"^see (?:me|us|him|her|them) (?:out|to|off|down|up)\b", re.IGNORECASE)
# A question tag on its own ("Don't you, Harold?") and a bare "tell it" (the robot) say nothing
# to do: both are said to somebody else in the room (text test v44)
_ASIDE = re.compile(r"^(?:(?:do|does|did|is|are|was|were|can|could|would|will|have|has)n'?t|won'?t) "
                    r"(?:you|he|she|it|they|we|i)$|^(?:tell|ask) it$"
                    # "look at it away down the hallway": the robot, talked about (text test v51)
                    r"|^(?:look|see) at (?:it|him|her|that thing|the robot|the wee thing)\b(?! and\b)"
                    # a question announced: "Tell me one thing, can that projector …?" (text test v121)
                    r"|^(?:tell me|let me ask(?: you)?|answer me|may i ask(?: you)?) (?:one thing|something|a thing"
                    r"|this|one question|a question)$"
                    # an attention-getter: "Listen carefully. Go to bedroom, …" (text test v129)
                    r"|^listen(?: (?:carefully|closely|up|here|to me|now|well))*$", re.IGNORECASE)
# "You drive in the kitchen", "Robot, you finish this call now": a request in the present
# tense, as a speaker of another first language says it (text test v49), for the robot's own
# actions (not "you make me laugh", "you drive like my husband", "you always go there")
_YOU_NOW = re.compile(rf"^you (?:{ROBOT_ACTIONS}|move|roll|finish|stop|make|take|get)\b"
                      r"(?! (?:me|us|him|her|them|like|so|too|very|really|fast|slow|well|badly|mad|crazy)\b)"
                      r"(?!.*\b(?:always|never|usually|often|sometimes|every|each|normally|ever|still|whenever|"
                      r"all the time|yesterday|last)\b)", re.IGNORECASE)
# "The doctor, Weber. You ring him." (text test v108): a call said to the robot, whole; not "you call him lazy"
_YOU_CALL = re.compile(r"^you (?:call|ring|phone|video|dial) (?:him|her|them)(?: (?:for me|for us|please|now))*\W*$",
                       re.IGNORECASE)
# "… and then Dr Weber on video for Baba" (text test v108): a person put on the screen
_ON_VIDEO = re.compile(r"^(?:(?i:dr\.?|doctor) )?[A-Z][a-z]+ on (?:the )?(?:video|screen|video call)\b"
                       r"(?!.*\b(?:was|were|is|are|had|has|looked|looks|seemed|said|told|yesterday|last)\b)")
# "I should like to know whether you are capable of taking yourself off …" asks what it can do (text test v65)
_KNOW_IF_ABLE = re.compile(r"^i(?:'d| would| should)? (?:like|love|want|wish) to know (?:whether|if) (?:you|it)"
                           r"(?:(?:'re| are| would be| might be| will be)? (?:capable|able)\b"
                           r"| (?:can|could|know how to)\b)", re.IGNORECASE)
# A word the shape of a request took for a verb, with a verb of telling after it: "first kitchen on the
# farm had a wood stove" (audio test v57: it drove to the kitchen) is about the kitchen, no request
_TOLD_OF = re.compile(r"\b(?:had|has|was|were|is|are|used to|looked|seemed|sounded)\b")  # ("…, looked tired")
# "kindly be going to the kitchen" (text test v49)
_BE_GOING = re.compile(r"^be (?:going|coming|heading|moving|off) (?:to|into|in|through|over|back)\b", re.IGNORECASE)
# a thing to be switched, said as what may happen to it: "the projector can go off now" (text v50)
_CAN_GO = re.compile(r"^(?:the|that|this|your|my) \w+ (?:can|could|may|should|ought to) "
                     r"(?:go|be (?:switched|turned|put)|come|get) (?:on|off)\b", re.IGNORECASE)
# a way to a place, said alone: "to the front door first", "from there on to the kitchen" (text test v50)
_TO_PLACE = re.compile(r"^(?=.*\b(?:first|next|then|now|please|last|again|from there|after that|back|straight|"
                       r"on to|onto)\b)(?:(?:from there|then|next|first|after that),? )?"
                       r"(?:(?:on|off|back|over|up|down|through|round|straight) )*(?:on)?to (?:the|my|your) \w+"
                       r"(?: \w+)?(?: (?:first|next|then|now|please|last|again|after that))*$", re.IGNORECASE)
# "Into the kitchen with you", "off to bed with ye": sent there (text test v119)
_WITH_YOU = re.compile(r"^(?:(?:off|back|away|up|down|out|over|on) )*(?:to|into|in to|onto) (?:the |your |my )?"
                       r"(?:\w+ )?(?:kitchen|room|lounge|bedroom|bathroom|hallway|hall|door|dock|charger|bed)"
                       r" with (?:you|ya|ye)\b", re.IGNORECASE)  # (not "to be honest with you")
# a place said alone after "now" (a filler before others): "Now the bathroom, and after, the bedroom" (text v102)
_NOW_PLACE = re.compile(r"^now,? (?:(?:on )?to |into )?(?:(?:the|your) )?(?:kitchen|living room|lounge|bedroom|bathroom"
                        r"|toilet|loo|hallway|hall|front door|door|dock|charger)$", re.IGNORECASE)  # not "now the news"
# home for its charge, said alone: "…, then home to charge", "then home for a charge" (text test v111)
# "then sit in the charger" (text test v121): the dock, asked
_SIT_ON_DOCK = re.compile(r"^(?:go and |go )?(?:sit|rest|settle) (?:yourself )?(?:in|on|at|back on) (?:the |your )?"
                          r"(?:charger|dock|charging dock|charging station|base)\b", re.IGNORECASE)
_HOME_TO_CHARGE = re.compile(r"^(?:(?:straight|right|back) )?home "
                             r"(?:to (?:re)?charge|for (?:a |your )?(?:re)?charg(?:e|ing))"
                             r"(?:,? (?:please|now|then))?\W*$",
                             re.IGNORECASE)
# a helm order: "set a course for the kitchen", "shape a course for the living room" (audio test v39)
_COURSE = re.compile(r"^(?:set|shape|plot|lay|steer) (?:a |your |our )?course (?:for|to)\b", re.IGNORECASE)
# "Off with the projector, please." (text test v37)
# … and "on" and "off" as verbs, as Nigerian English says them: "off the projector", "on the projector
# so she can see" (text test v65); not a place ("on the table", "off the kitchen": no thing switched)
_ON_OFF_WITH = re.compile(r"^(?:on|off) with (?:the|that|your|this|my) \w+"
                          r"|^(?:on|off) (?:the|that|your|this|my) (?:projector|telly|tv|television|screen|lamp"
                          r"|light)s?"
                          r"(?: (?:so|then|and|please|now|for|also|too|as well)\b|$)", re.IGNORECASE)  # "… also" (v129)
# a thing switched, said first: "projector on for my drama" (text test v105: no step)
_SWITCHED = re.compile(r"^(?:the |that |your |my )?(?:projector|telly|tv|television|screen)s? (?:on|off)\b"
                       r"(?! (?:the|a|my|your|its|this|that|these|those)\b)", re.IGNORECASE)  # "… on this thing is …"
# what the speaker will do themselves: "First let me find my glasses" (text test v105: put first, then the call)
_LET_ME = re.compile(r"^let me (?!(?:know|see|hear|talk|speak|have|call|ring|phone|video)\b)\w+", re.IGNORECASE)
# "The bedroom's where I need you", "kitchen is where you should be": a place asked for
_WHERE_WANTED = re.compile(r"(?:'s| is) where " + WANTED_THERE, re.IGNORECASE)
_COPULA = frozenset({"is", "are", "was", "were"})
_NOUNS_TOO = frozenset({"call", "video", "ring", "phone", "drive", "charge"})  # (not "check are the windows shut")
_SUBJECTS = frozenset({"i", "we", "he", "she", "they", "it", "that", "this", "there", "you"})  # "I'm off now"
_WH = frozenset({"what", "where", "which", "who", "when", "how"})
# right after a question word, these ask nothing: "where I left my hymn book" (text test v46)
_TELLS = frozenset({"i", "we", "he", "she", "they", "my", "our"})
_ASKS_WITH = frozenset({"now", "then", "for", "else", "much", "many", "far", "long", "come", "so", "about"})
# Verbs that ask the robot to carry on as it is: no action, unless a place follows ("wait in the hallway").
_HOLD = frozenset(["stay", "wait", "keep", "carry", "continue", "remain", "hold"])
# carrying on where it is going, said with the place the person thinks it goes to: "Nah, don't stop,
# keep going to the kitchen" (text test v134: a drive to the front door was sent to the kitchen)
# ("carry on to the bedroom" after a drive is the next step: text tests v14, v16, v23)
_KEEP_GOING = re.compile(r"^keep(?: on)? (?:going|driving|moving|rolling|heading) (?:on )?(?:to|towards|into) ")
# an unsure opening before a command (not `lexicon._HEDGE`, a hedge said alone after a request)
_UNSURE = re.compile(r"^(?:i guess|i suppose|i think|maybe|perhaps),?\s+")
# (or a room with no article, as a second language says it: "wait for us in living room", text test v98)
_PLACE = re.compile(r"\b(?:in|at|by|to|into|near) (?:the|my|your|(?=(?:kitchen|living room|bedroom|bathroom|hallway"
                    r"|front door|dock|charger)\b))", re.IGNORECASE)
# why it goes, not a step: "…, pop off to the kitchen and leave us to it" (text test v92)
_LEFT_TO_IT = re.compile(r"^leave (?:us|me|them|him|her)(?: (?:two|both|all))? to (?:it|(?:our|their) \w+)\b")
# how to walk, said to a person: no place, no step ("…, Mkhulu, walk slowly hey", text test v94: it drove there)
_MANNER_ONLY = re.compile(r"^(?:walk|step|tread|move|go)(?: (?:very|really|nice and|more|extra))? (?:slowly|slow|"
                          r"carefully|careful|gently|easy)(?:,? (?:now|please|hey|eh|ok|okay|mind|love|dear))*\W*$")
# "I was gonna tell you to stop, but …": a stop nearly said is no stop (text test v57)
_WAS_GOING_TO = re.compile(r"\b(?:was|were) (?:going to|about to|meaning to|gonna) (?:tell|ask|say)\b"
                           r"|\b(?:nearly|almost) (?:told|asked|said)\b", re.IGNORECASE)


def classify(clause: str) -> ClauseKind:
    opening = FILLER.match(clause.strip())  # what is said before a request without changing it
    said_first = opening.group(0) if opening else ""
    text = clause.strip()[len(said_first):].strip()
    lowered = text.lower()
    if not text or RHETORICAL.match(text):
        return ClauseKind.STATEMENT
    if _ASIDE.match(text) or DO_THOSE.match(text) or (HABIT.search(lowered) and not STOP.search(lowered)) \
            or _LEFT_TO_IT.match(lowered) or _MANNER_ONLY.match(lowered) or _LET_ME.match(lowered) \
            or _LOOK_HOW.match(lowered):
        return ClauseKind.STATEMENT  # (text test v48: "…, so stop worrying." stopped the robot)
    if STOP.search(lowered) and not re.search(r"\b(?:(?:don'?t|do not|never|no need to|needn'?t|not)(?: you)?"
                                               # "I don't want you to stop" (text test v59)
                                               r"(?: (?:want|need|mean|ask|tell|have|has)\w* (?:you )?to)?"
                                               r"|(?!you\b)\w+ "
                                               r"(?:can'?t|cannot|couldn'?t|won'?t)) (?:stop|\w+ still)\b", lowered) \
            and not _WAS_GOING_TO.search(lowered):
        return ClauseKind.REQUEST  # a stop is always a request
    if _SUGGEST.search(lowered) and not _CALL_OFF.search(lowered) and not LATER.search(lowered):
        return ClauseKind.REQUEST
    if (_CALL_OFF.search(lowered) or _NEGATION.search(_MIND.sub("", lowered)) or LATER.search(lowered)
            or re.match(r"^no\b", lowered)):
        return ClauseKind.NEGATED
    if _CHALLENGE.match(lowered):
        return ClauseKind.REQUEST  # "let's see if you can find your own way back" is to be done (text test v47)
    if asks_ability(text) or _KNOW_IF_ABLE.match(lowered):
        return ClauseKind.ABILITY
    if _POLITE.search(lowered) or (IN_ORDER.search(said_first) and YOU_DO.match(lowered)) or _YOU_NOW.match(lowered) \
            or _YOU_CALL.match(lowered) or _ON_VIDEO.match(text) \
            or _BE_GOING.match(lowered):
        return ClauseKind.REQUEST  # "could you …"; "first you go to bathroom": a step said to the robot
    said = words(lowered)
    if not said:  # no word in Latin letters ("Будь ласка,": Ukrainian please, text test v98): nothing asked
        return ClauseKind.STATEMENT
    first = said[0]
    if first in _NOUNS_TOO and len(said) > 1 and ({said[1], *said[2:3]} & _COPULA):
        return ClauseKind.STATEMENT  # "Video call is only for Anna, …?": the thing talked of (text test v121)
    if first == "do" and ((len(said) > 1 and said[1] in IMPERATIVES)
                          or re.search(r"\b(?:please|kindly)\W*$", said_first, re.I)):
        return ClauseKind.REQUEST  # an emphatic "do go to the bathroom"; "please do one video call"
    if first in _HOLD and (not _PLACE.search(lowered) or _KEEP_GOING.match(lowered)):
        return ClauseKind.STATEMENT  # "stay here", "keep driving", "keep going to the kitchen": nothing to do
    if (hedged := words(_UNSURE.sub("", lowered))) and hedged[0] in IMPERATIVES and len(hedged) < len(said):
        return ClauseKind.REQUEST  # "I guess head back to the dock": a command said unsurely (text test v69)
    if first in IMPERATIVES or ((shape := IMPERATIVE_SHAPE.match(lowered)) and not NOT_A_VERB.match(shape.group(1))
                                and not _TOLD_OF.search(lowered[shape.end():])):
        return ClauseKind.REQUEST
    if _LOOK.match(text) or _ON_OFF_WITH.match(text) or _WHERE_WANTED.search(text) or _SEE_OFF.match(text) \
            or _COURSE.match(text) or _CAN_GO.match(text) or _TO_PLACE.match(text) or _NOW_PLACE.match(clause.strip()) \
            or _SWITCHED.match(text) or _HOME_TO_CHARGE.match(text) or _WITH_YOU.match(text) \
            or _SIT_ON_DOCK.match(text):
        return ClauseKind.REQUEST
    if first in _WH and len(said) > 2 and said[1] in _TELLS:
        return ClauseKind.STATEMENT  # "…, where I think I left my hymn book": a place described, no question
    if first.split("'")[0] in QUESTION_WORDS:  # also "what's", "where's", "how's"
        if len(said) <= 2 and first in _WH and (len(said) == 1 or said[1] not in QUESTION_WORDS | _ASKS_WITH):
            return ClauseKind.STATEMENT  # "What... what time... it's so dark": a word searched for, no question
        return ClauseKind.QUESTION
    if ((len(said) <= 3 and (said[-1] in ("on", "off", "please", "now") or HASTE.match(said[-1])))
            # "the projector off now" (a dev case of the thirty-fifth session; not "the telly's off now")
            or (len(said) == 4 and first in ("the", "that", "this", "your", "my") and said[-2] in ("on", "off")
                and said[-1] in ("now", "please") and "'" not in said[1])) \
            and first.split("'")[0] not in _SUBJECTS and first != "enough":
        # a terse command: "projector on", "kitchen, please" (not "enough now": the stop's and the
        # cancel's, when the robot moves, `halting.halts`; before a request, no step: text test v64)
        return ClauseKind.REQUEST
    return ClauseKind.STATEMENT
