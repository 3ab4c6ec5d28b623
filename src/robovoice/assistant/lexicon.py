"""The words `intent` reads requests with, and how it splits them (`words`): verbs that start a
request, question words, words that make an object specific, the verbs a person's own plan may
ask the robot for, the base form of a participle ("once you've gone to the bedroom" is "go
to the bedroom"), and whether a request was cut off before its object (`unfinished`)."""

from __future__ import annotations

import re

from robovoice.assistant.code_switch import in_english
from robovoice.assistant.formal import as_asked
from robovoice.assistant.misheard import heard_right
from robovoice.assistant.texting import from_texting
from robovoice.assistant.word_finding import words_found


def words(text: str) -> list[str]:
    """The words of `text`, lower-cased, apostrophes kept ("what's", "son's")."""
    return re.findall(r"[a-z0-9']+", text.lower().replace("\u2019", "'"))


# Said before or around a request without changing it.
FILLER = re.compile(
    r"^(?:(?:(?:just|wait) a (?:sec|second|minute|moment|mo)|please|abeg|kindly|now|ok|okay|so|oh|well|right|alright|"
    r"also|instead|first of all|to (?:begin|start) with|first|quickly|"
    r"firstly|second|secondly|third|thirdly|lastly|last of all|next|finally|just|off you|i mean|i meant|"
    r"(?:and )?(?:at|in) the (?:very )?end|"  # "…, and at the end back to your dock" (text test v98)
    r"one (?:sec|second|moment)|hey|hi|robot|jarvis|and|then|yes|yeah|actually|sorry|hang on|hold on|oh dear|"
    r"erm|er|um|umm|uh|uhh|uhm|hmm|mm+|mhm|ah|ahh|aah|aw|k|like|what am i saying|what was i thinking|silly me|y'all|yo|"
    r"bro|bruh|dude|yaar|arre|arey|accha|achha|acha|"  # young people's and Hinglish openers (text test v68)
    r"ay|oy vey|oy|oye|nu|hoy|oi|"  # Spanish, Yiddish (text test v69) and Tagalog ones (text test v76)
    r"aiyah|aiya|aiyoh|aiyo|alamak|walao|wah|"  # Singlish ones (text test v70)
    r"eh|ehh|though|tho|"  # (text test v113: "Call Ben. Eh, sorry, …" made a step of the "Eh")
    r"bismillah|alhamdulillah|mashallah|masha'?allah|subhanallah|wallahi|"  # (text test v114: a step of "Bismillah")
    r"aye|och|ach|"  # Scots ones (text test v74)
    r"(?:i'?ll )?tell you what|"
    # "um, chuck the projector on" heard "I'm Chuck the projector on" (audio test v83): no "I'm" takes a bare verb
    r"i'?m(?=[\s,]+(?:go|call|ring|phone|dial|turn|switch|chuck|head|drive|end|hang|stop|pop|nip|bring|take)\b)|"
    r"wait(?=[\s,]+(?:what|which|where|who|how|why|when|do|does|did|is|are|can)\b))\b[\s,]*)+",
    re.IGNORECASE,
)
# haste said after a request: "Hallway, and quick about it." (a tag; after a bare place it asks for it)
_HASTE = (r"(?:and )?(?:be )?(?:quick|sharp|snappy)(?: about it)?|(?:and )?(?:sharpish|smartish)|chop chop|pronto|"
          r"quick smart|quick,? quick|"  # (text test v55; v106)
          r"(?:real|really|super) quick(?: like)?|asap|right away|straight away|at once|"  # (text test v63)
          r"(?:and )?step on it|on the double|(?:as )?quick as (?:you can|you like)|"
          r"(?:go )?fast(?: fast)?|"  # (dev valueonly-1)
          # … and how to go: "bathroom, please, quietly" (audio test v33)
          r"(?:please,? )?(?:and )?(?:nice and )?(?:quiet(?:ly)?|slow(?:ly)?|careful(?:ly)?|gently|soft(?:ly)?|quickly)"
          r"(?:,? (?:now|please))?")
HASTE = re.compile(rf"^(?:{_HASTE})$", re.IGNORECASE)
TAG = re.compile(r"^(?:(?:would|will|could|can|won'?t|wouldn'?t|can'?t) (?:you|ye)(?: please| like)?|"
             r"if you (?:would|could|please|wouldn'?t mind|don'?t mind)|"
             r"(?:pretty )?please|thanks|thank you|dear|love|pet|darling|my dear|i mean|mind|mate|pal|hen|duck|petal|"
             rf"sweetheart|lovey|{_HASTE}|"
             # thanks, and what the robot is called in passing ("Away through to the living room, son, …":
             # not a call to the person's son, text test v37; "my son" is someone)
             r"ta|cheers|ta very much|son|lad|lass|sunshine|buddy|chief|kiddo|young man|my lad|my boy|my girl|"
             r"(?:muchas )?gracias|mija|mijo|mi amor|shukriya|dhanyavaad|"  # (text test v69)
             # Southern US (text test v71), Jamaican London and Ghanaian (v72), Maltese (v73)
             r"hon|honey|sugar|sweetie|bruv|bredda|chale|grazzi|"
             # Scots and Gaelic (text test v74): endearments, thanks, the emphatic "…, so it is"
             r"(?:a|mo) ghr[aà]idh|(?:a|mo) chridhe|a charaid|m'eudail|a st[oò]ir|tapadh (?:leat|leibh)|"
             r"(?:m[oò]ran )?taing|sl[aà]inte|"
             r"anak|iho|iha|hijo|hija|ha|diba|sige|salamat(?: po)?|"  # Tagalog (text test v75)
             r"so (?:it|i|you|we|they|he|she) (?:is|am|are|does|do|will))$",
             re.IGNORECASE)

# Putting a request off.
LATER = re.compile(
    r"\b(?:later|tomorrow|tonight|this evening|this afternoon|next week|one day|some day|someday|"
    r"in an? (?:hour|minute|while)|"
    r"in \w+ (?:hours|minutes)|after (?:(?:his|her|my|our|your|their) )?(?:lunch|dinner|breakfast|tea|supper)|until)\b"
    # … and after anything of the person's, said last: "Go to the kitchen after my puja" (audio test v123)
    r"|\bafter (?:his|her|my|our|their) (?!call\b)\w+(?=\s*(?:[.,!?]|$))",
    re.IGNORECASE,
)

IMPERATIVES = frozenset({
    "go", "drive", "come", "move", "head", "roll", "walk", "make", "take", "bring", "turn", "switch", "put",
    "power", "start", "stop", "end", "hang", "call", "ring", "phone", "dial", "video", "connect", "get",
    "tell", "show", "check", "look", "list", "read", "cancel", "return", "park", "wait", "stay", "halt",
    "freeze", "charge", "find", "play", "open", "close", "give", "let", "keep", "carry", "help", "pop",
    "leave", "forget", "abort", "quit", "finish", "send", "fetch", "navigate", "dock", "hurry", "follow", "facetime",
    "join", "photograph", "snap", "capture", "shut", "try", "nip", "plug", "trot", "toddle", "scoot", "wander", "zip",
    "kill", "gie", "enter",  # "kill the projector"; Scots "gie Clara a call" (give); "enter the kitchen"
    "place", "telephone", "proceed",  # formal: "place a call to …", "proceed to the living room"
    "hit", "dip", "bounce",  # young people's: "hit up Clara", "dip to the hallway"
    "steer",  # "steer for the bathroom" (text test v48)
    "ping", "drop",  # a gadget's words: "ping Ben on video", "drop the call" (text test v54)
    "disconnect",  # "please disconnect this call now" (audio test v40)
    "cut",  # "cut the call now" (text test v68)
    "fly", "dash",  # a child's drive: "your cave is the bedroom, so fly there" (text test v133)
    "fire",  # "fire the projector up" (text test v82)
    "douse",  # "douse the projector" (text test v63)
    "holler",  # Southern US: "holler at Dr. Weber for me" (text test v71)
})
# The word that asks the robot to stop: a spoken stop is always for it (intent, addressee)
# "hold still" said to the robot, not of it ("do you have to stay still?", "the kids won't keep still")
# A habit to give up ("stop worrying", "stop fussing over me"), said to a person: no stop of the
# robot ("stop moving", "stop driving" are)
_HABIT = (r" (?!(?:mov|driv|go|roll|runn|turn|spinn|follow|com|wander|head|travell|walk|creep|edg|trundl)ing\b)"
          r"(?!(?:every|some|any|no)?thing|(?:r|br|s|dur|morn|even|ceil|k|w|str|spr)ing\b)[a-z]{2,}ing\b")
HABIT = re.compile(rf"\b(?:stop|quit){_HABIT}", re.IGNORECASE)
# ("stop stop talking", as a misheard "that's us done talking" was heard: audio test v42)
STOP = re.compile(rf"\bstop\b(?!(?:,? stop)*{_HABIT})|(?<![\w'] )\b(?:hold|keep|stay|stand) (?:still|stock-still)\b"
                  r"|\bhold it (?:right )?there\b", re.IGNORECASE)  # (text test v49)
# The robot's own actions, as verbs after "you": "Robot, you ring Anna" (addressee), "you go in
# the kitchen" (clause_kind)
ROBOT_ACTIONS = ("go|drive|head|come|ring|call|phone|dial|video|switch|turn|put|return|cancel|end|hang|pop|nip"
                 "|close|finish")  # "robot, you close the call" (text test v101)
# "First you go to bathroom": after an ordering word, "you" and an imperative is a step asked
IN_ORDER = re.compile(r"\b(?:first|firstly|next|then|finally)\b", re.IGNORECASE)
YOU_DO = re.compile(rf"^you (?:{'|'.join(sorted(IMPERATIVES))})\b", re.IGNORECASE)


QUESTION_WORDS = frozenset({
    "what", "where", "whereabouts", "which", "who", "whom", "whose", "when", "why", "how", "is", "are", "am", "do",
    "does", "did", "have", "has", "was", "were",
})

NOT_GENERIC = frozenset({
    "the", "my", "your", "his", "her", "their", "our", "this", "that", "these", "those", "to", "into", "in", "on",
    "at", "for", "us", "is", "was", "has", "does", "yes", "please", "thanks", "as", "its", "it's", "hers",
    "yours", "ours", "theirs", "anywhere", "always", "sometimes",
})

ASKING_VERBS = frozenset({"talk", "speak", "call", "ring", "phone", "video", "chat", "see", "know", "check", "hear",
                           "find"})

# Who a person is to the speaker: "my daughter … get her on the video" names someone. ("The
# doctor" is not here: it names Dr. Weber by title, so a "him" after it is checked as a name.)
RELATIONS = frozenset({"son", "daughter", "neighbour", "neighbor", "gp", "sister", "brother", "mum", "mom",
                       "mother", "dad", "father", "wife", "husband", "grandson", "granddaughter", "friend", "carer",
                       "nurse", "niece", "nephew", "aunt", "auntie", "uncle", "cousin"})

# the little words before a place or a person ("the kitchen", "to my son"): no part of what is named
# a thing named as where something is, not what is acted on: "keep the photo right next to the projector"
# (audio test v99, misheard: it switched the projector on; `fit.fits`)
BESIDE = re.compile(r"\b(?:right |just )?(?:next to|beside|behind|near|under(?:neath)?|in front of|on top of|close to)"
                    r" (?:the|my|your|that|this|our) \w+", re.IGNORECASE)
ARTICLES = frozenset({"the", "a", "my", "your", "to"})
NOT_NAMES = frozenset({"the", "my", "your", "a", "an", "that", "this", "it", "one", "out", "off", "on", "for", "now",
                       "please"})

_IRREGULAR = {"gone": "go", "been": "go", "had": "have", "got": "get", "gotten": "get", "made": "make", "rung": "ring",
              "taken": "take", "driven": "drive", "done": "do", "found": "find", "told": "tell", "shown": "show",
              "brought": "bring", "left": "leave", "run": "run", "come": "come", "put": "put", "shut": "shut",
              "phoned": "phone", "rang": "ring", "dialled": "dial", "switched": "switch", "hung": "hang"}


def base_form(participle: str) -> str:
    """The verb a request would use: "gone" → "go", "checked" → "check", "parked" → "park"."""
    word = participle.lower()
    if word in _IRREGULAR:
        return _IRREGULAR[word]
    if word.endswith("ied"):
        return word[:-3] + "y"
    if word.endswith(("pped", "tted", "gged", "nned")):
        return word[:-3]  # "popped" → "pop"
    if word.endswith(("ved", "ged", "ced", "zed", "ated")) or (word.endswith("sed") and not word.endswith("ssed")):
        return word[:-1]  # "charged" → "charge", "closed" → "close"
    return word.removesuffix("ed")


# An imperative's shape around a verb no list has ("trundle over to the door", "shoot off back to
# your charger", "wheel yourself in", "crank up the projector", "whack the projector on"): a bare
# first word, then "yourself", a way to a place, or up/on/off a thing. Not a pronoun, a past
# tense, a gerund or a plural ("went over to", "lights on the").
IMPERATIVE_SHAPE = re.compile(r"^(\w+) (?:yourself\b|(?:(?:on|off|over|along|across|back|down|up|round|around|"
                              r"through|out|ben) ){0,2}(?:to|into|towards?|by|tae|intae|ben) (?:the|my|your|bed)\b|"
                              r"(?:up|on|off) (?:the|my|your|that|this) |(?:the|my|your) \w+ (?:on|off)\b"
                              r"(?! (?:the|this|that|my|your|a|an|his|her|our|their|its)\b))")
# (a gerund's "-ing" is not that of "swing", "bring", "ring")
NOT_A_VERB = re.compile(r"^(?:i|you|he|she|we|they|it|this|that|these|those|there|here|the|a|an|my|your|his|her|"
                        r"our|their|someone|somebody|nobody|everyone|went|came|ran|drove|got|took|rode|fell|sat|"
                        r"stood|left|is|are|was|were|am|be|been|has|have|had|do|does|did|can|could|would|will|"
                        r"should|shall|may|might|must|past|through|behind|beside|along|across|towards?|near|under|"
                        r"over|round|around|beyond|inside|outside|opposite|next|between|below|above|"
                        r"(?!(?:sw|br|r|s|fl|sl|st|wr|str)ing$)\w+(?:ed|ing|[^s]s))$")

# A bare "no", "don't", "don't bother", "scratch that" after a request takes it back.
WITHDRAWAL = re.compile(r"^(?:(?:no|nope|don'?t(?: bother| do that| worry)?|do not|scratch that|not that|belay that|"
                        r"forget (?:it|that|(?:that )?i (?:said|asked)(?: that| it)?|what i (?:said|asked))|"
                        r"never ?mind|cancel that|scrap (?:that|it)|on second thoughts?|no,? wait|wait,? no|"
                        r"no,? (?:hang|hold) on|"  # "go to the kitchen, no hang on, not yet" (audio test v88)
                        r"no,? actually|actually,? no|"
                        r"leave (?:it|that)|no need(?: (?:already|anymore|any more|now|then))?"  # (text test v70)
                        r"|not (?:necessary|needed))"  # "Call Clara? Nu, bine, not necessary, …" (text test v98)
                        r"\b[\s,]*)+$",
                        re.IGNORECASE)
# "…, I want to show her my cake": after a request, the person's own plan is the reason for it,
# unless it asks the robot for a call or to find something out ("…, I'd like to talk to Anna")
OWN_PLAN = re.compile(r"^i(?:'d|'ve| would)? (?:(?:really|only|just|very much) )?"
                      r"(?:want|need|wish|like|have|got) to (\w+)",
                      re.IGNORECASE)
# Taking back one thing by its name: "not Ben", "skip the kitchen", "leave Clara", "forget about the call".
# (not "leave us to it": why it goes, text test v92)
NOT_THAT = re.compile(r"^(?:not|skip|leave(?! (?:us|me|them|him|her) to\b)|forget(?: about)?|drop|scratch|scrap|cancel)"
                      r"\s+((?:\w+\s*){1,3})$",
                      re.IGNORECASE)
# A clause that only says when, not what: "Later on, after lunch, you can go back to your
# charger": what follows in the same breath is postponed too.
LATER_ONLY = re.compile(r"^(?:(?:later(?: on)?|tomorrow(?: morning| afternoon| evening)?|tonight|this (?:evening|"
                        r"afternoon)|after (?:lunch|dinner|breakfast|tea)|in an? (?:bit|while|hour|minute|moment)|"
                        r"some other time|another time)\b(?:[\s,]+(?:perhaps|maybe|i think|or so|only))?[\s,]*)+$",
                        re.IGNORECASE)  # "Later on, after lunch perhaps, …" (text test v63)
# An exclamation said as a question, not a request: "…, can you believe it!", "would you believe it?"
RHETORICAL = re.compile(r"^(?:can|could|would|will) (?:you|ye) (?:ever )?(?:believe|imagine|credit)\b"
                        r"(?: (?:it|that|this|them|him|her|the (?:cheek|nerve)(?: of (?:it|him|her|them))?))?\W*$",
                        re.IGNORECASE)

# Words for the person on the call, not a step for the robot: "tell Anna cheerio (from me)", "say
# ta-ra to our Ben", "wish Clara goodnight", "tell Anna I'm flagging", "love to the kids, speak
# Sunday". The robot passes no messages; the person says them.
_PARTING = (r"(?:bye|bye-bye|bye bye|goodbye|good-bye|good bye|cheerio|ta-ra|tara|ta ta|so long|farewell|"
            r"good ?night|night night|see you|hello|hi|thanks|thank you|all the best|best wishes|my love)")
FAREWELL = re.compile(rf"^(?:(?:tell|wish|bid) (?:our |my )?\w+(?: \w+)? (?:a |my )?{_PARTING}"
                      rf"|say (?:a )?{_PARTING}(?: to\b| for me\b|$)"
                      # a message ("tell Anna I'm flagging", "tell him that …"; not "tell me …")
                      r"|tell (?!me\b|us\b)(?:our |my )?\w+(?: \w+)? (?:that|i|i'\w+|we|we'\w+|it|it's|he|he's|she"
                      r"|she's|they|they're)\b"
                      # partings said into the call: "love to the kids", "speak Sunday", "take care"
                      r"|(?:(?:give|send) (?:them |him |her )?)?(?:my |all my |lots of |much |our )?"
                      r"love to\b"
                      r"|(?:speak|talk|see you|catch you)(?: to you| with you)?(?: on| next| this)? "
                      r"(?:soon|later|tomorrow"
                      r"|(?:mon|tues|wednes|thurs|fri|satur|sun)day|the weekend|next week)\b|take care\b"
                      r"|mind how you go\b)", re.IGNORECASE)

# A hedge said after a request: "…, then go and wait at the front door for her, I guess" (text
# test v26). It asks nothing, though it is short enough to look like "…, then the bedroom".
_HEDGE = re.compile(r"^(?:i (?:guess|suppose|think|reckon|expect|imagine)|you know|y'know|if you like|or something"
                    r"|or whatever|i'd say|mind you)$", re.IGNORECASE)
# a person doing something, said in two words ("…, she waits", "he knows"): no place or person asked for
_SUBJECT_VERB = re.compile(r"^(?:he|she|they|we|i|it|there) \w+$")


# A place or a thing, then what it is for ("the front door to see me out"; not "the kids want to …")
_PURPOSE = re.compile(r"^((?:(?:to|into|in|at) )?(?:the|my|your) \w+(?: \w+)?)(?<!\bwant)(?<!\bwants)(?<!\bneed)"
                      r"(?<!\bneeds)(?<!\blike)(?<!\blikes)(?<!\bhave)(?<!\bhas)(?<!\bgot)(?<!\bused)(?<!\bgoing)"
                      r"\s+(?:to|so as to|in order to) (?!(?:the|my|your|a|an|his|her|our|you)\b)\w+.*$")


# "… Okay, do those two.": what was just listed, asked again; no step of its own (text test v45)
DO_THOSE = re.compile(r"^(?:do|carry out|follow) (?:those|these|them|both|all (?:of )?(?:those|these|them|that))"
                      r"(?: (?:two|three|four|things|steps|instructions))?(?: (?:please|now|for me|then))*$",
                      re.IGNORECASE)


# "stay put", "stay where you are": a verb of keeping as things are, never a verbless continuation ("Go to
# the kit... no. No, don't. Stay put." read "stay put" as the place corrected to: text test v53)
_HOLD_STILL = re.compile(r"^(?:stay|remain)\b")
# a remark on the job, no thing in it ("go to the kitchen then call anna. easy": text test v118)
_REMARK = re.compile(r"^(?:easy(?: peasy)?|simple|nice one|lovely|great|perfect|brill(?:iant)?|sorted|cool|ace"
                     r"|fab|super|awesome|ta|cheers|thx|ty|lol|haha|x+|k+|done|job done|that's it|thats it)(?: x+)?$")


def fragment(part: str) -> bool:
    """A verbless continuation: "the bedroom", "to the front door", "Ben" (not a hedge: "I guess")."""
    text = FILLER.sub("", part.strip()).strip().lower()
    # "back to bed with you"; "living room instead" (text test v68)
    text = re.sub(r"\s+(?:after that|afterwards|after|next|too|as well|with you|instead)$", "", text)
    text = _PURPOSE.sub(r"\1", text)  # what it is for: "the front door to see me out"
    return not _HEDGE.match(text) and not _SUBJECT_VERB.match(text) and not DO_THOSE.match(text) \
        and not _HOLD_STILL.match(text) and not _REMARK.match(text) and bool(re.match(
        r"^(?:back |on |over |then |next )?(?:to |into |onto |in |at |on |with )?(?:the |my |your )?\w+(?: \w+)?$",
        text))


# An utterance whose last request ends on a word that needs one after it was cut off
# (speech-to-text keeps what was said: "please switch the…", "can you drive over to?"); the
# model would fill in the rest. A preposition may end a finished request whose object came
# before it ("list the places you can drive to"); an article or a conjunction may not.
_ENDS_ON_ARTICLE = re.compile(r"\b(?:the|a|an|my|your|and|or)\s*(?:\.\.\.|\u2026)?[\s.?!]*$", re.IGNORECASE)
_ENDS_ON_PREPOSITION = re.compile(r"\b(?:to|into|onto|with|at|for|of|from)\s*(?:\.\.\.|\u2026)?[\s.?!]*$",
                                  re.IGNORECASE)
_OBJECT_BEFORE = re.compile(r"\b(?:the|which|what)\s+\w+(?:\s+\w+)?\s+(?:that\s+|which\s+)?(?:you|i|we|they)\b",
                            re.IGNORECASE)


def unfinished(clause: str) -> bool:
    """The request ends where a word must follow: the person was cut off."""
    text = clause.strip()
    return bool(_ENDS_ON_ARTICLE.search(text)) or bool(_ENDS_ON_PREPOSITION.search(text)
                                                         and not _OBJECT_BEFORE.search(text))


# Typed the way people text, and "pleeease": the words as a request reads them ("can u ring ben
# pls" is "can you ring ben please"; "please to call my daughter", as a learner says it)
_TEXTED = {"u": "you", "ur": "your", "urself": "yourself", "pls": "please", "plz": "please", "thx": "thanks",
           "n": "and", "rn": "right now", "bot": "robot", "ngl": "honestly", "tbh": "honestly", "imo": "honestly",
           "fr": "really", "btw": "by the way", "idk": "I don't know", "rly": "really", "nah": "no", "naw": "no",
           "wanna": "want to", "gonna": "going to", "gotta": "got to",  # "after that I wanna call Ben" (text v56)
           "ty": "thank you", "vid": "video", "nvm": "never mind",  # "vid call Ben", "… rung Ben. ty" (text v60, v59)
           "r": "are", "w": "with", "lowkey": "really"}  # "my hands r full", "hang up w anna" (text test v118)
# "once ur in the kitchen": you're, before where or how it is (text test v60); else "your"
_UR_ARE = re.compile(r"\bur(?= (?:in|at|on|by|there|here|back|done|finished|going|not|so|a|an|the|nearly|almost"
                     r"|\w+ing)\b)", re.IGNORECASE)
_TEXTED_WORD = re.compile(r"\b(" + "|".join(_TEXTED) + r")\b", re.IGNORECASE)
_STRETCHED = re.compile(r"([a-z])\1{2,}", re.IGNORECASE)  # a letter said three times or more ("pleeease")


# A checklist's numbers ("Number one, projector on. Item two: the bedroom.") are its order words.
_NUMBERED = re.compile(r"(?:(?<=^)|(?<=[.!?;:,]\s))(?:number|item|step|point|task|job) (one|two|three|four|five)"
                       r"\s*[:,.)-]?\s*", re.IGNORECASE)


# A quotation mark (not an apostrophe inside a word: "don't", "Ben's")
_QUOTE = re.compile(r"(?<!\w)['\u2018\u2019\"\u201c\u201d]+|['\u2018\u2019\"\u201c\u201d]+(?!\w)")


def plain(text: str) -> str:
    """`text` with texting shorthand spelled out, stretched letters said once and a checklist's
    numbers said as order words ("first", "then")."""
    text = in_english(as_asked(words_found(text)))  # "prende el projector", "projector band karo" (v69, v68)
    text = _TEXTED_WORD.sub(lambda m: _TEXTED[m.group(1).lower()], _UR_ARE.sub("you're", _STRETCHED.sub(r"\1", text)))
    text = from_texting(text)  # "… anna you can hang up now", "need you in the bathroom" (text test v118)
    text = _NUMBERED.sub(lambda m: "first " if m.group(1).lower() == "one" else "then ", text)
    text = _QUOTE.sub("", text)  # "Step four: 'send the robot to the dock'": the words read out
    text = heard_right(text, IMPERATIVES)  # "the project or", "finish the coil", "…, end the front door"
    text = _LET_GO.sub(r"end the call with \1", text)  # "Let Anna go now": the call, ended (text test v119)
    text = _FINISH_WITH.sub(r"end the call with \1", text)  # "Finish with Anna now, …" (text test v120)
    # "Put the, um, the picture thing on": one clause (text test v38)
    text = _HESITATION.sub(lambda m: m.group(1) or m.group(2), text)
    text = _THATS_WHERE.sub(r"\1 is where", text)  # "The bedroom, that's where I need you": one clause
    text = _SO_KIND_AS_TO.sub("please", text)  # a courtesy, not a condition
    text = _GO_AHEAD.sub("", text)  # "Go ahead and hang up now": no drive, one request (text test v71)
    text = _NO_TAG.sub(".", text)  # "tell it to go to the bedroom, no?": a tag asking agreement (text test v61)
    text = _WAIT_NO.sub(" ", text)  # "Call Dr. Weber... wait, no need": taken back, no stop (text test v70)
    text = _NEXT_DOOR.sub("nextdoor", text)  # "Clara next door": the neighbour's, no door of the home (text test v58)
    # "can u like, play netflix on that projector or nah": one question, "or not" (text test v84)
    text = _OR_NAH.sub(lambda m: f"{m.group(1) or ''}or not", _ASK_LIKE.sub(r"\1 ", text))
    return re.sub(r"\bplease to (?=\w)", "please ", text, flags=re.IGNORECASE)


# … in Polish and Czech too: "…, so first hallway, tak?" ("tak" was read as Scots "take": text test v111)
_LET_GO = re.compile(r"\blet ((?-i:[A-Z])[a-z]+|her|him) go\b(?! (?:to|into|in|and|through|out|back)\b)",
                     re.IGNORECASE)
# told to, at the start of a clause: "Finish with Anna now" ("I'll finish with Anna's photos" is no call)
_FINISH_WITH = re.compile(r"(?:^|(?<=[,.;:!?] ))(?:finish|wrap (?:it )?up|be done) with "
                          r"((?-i:[A-Z])[a-z]+|her|him)\b(?!')", re.IGNORECASE)
_NO_TAG = re.compile(r"(?<=\w),\s*(?:no|tak|ano|prawda|dobrze|dobře|jo)\?", re.IGNORECASE)
_GO_AHEAD = re.compile(r"\bgo ahead and (?=\w)", re.IGNORECASE)
_WAIT_NO = re.compile(r"(?<=[.,!?;\u2026\u2014-]) *wait[,!.\u2026]*\s+"
                      r"(?=(?:no|nah|actually|never mind|forget|scratch)\b)", re.IGNORECASE)
_NEXT_DOOR = re.compile(r"\bnext door\b", re.IGNORECASE)
_ASK_LIKE = re.compile(r"\b((?:can|could|would|will) (?:you|u|ya)) like\s*,\s*(?=\w)", re.IGNORECASE)
_OR_NAH = re.compile(r"\bor (?:nah+|naw|nope|no)\b(?=\s*(?:[?.!,]|$))"
                     # "or what" after a question only ("Call Ben or what?" is impatience, a request)
                     r"|(\b(?:can|could|would|will|do|does|is|are) (?:you|u|ya|it) [^.!?]*?)\bor what\b",
                     re.IGNORECASE)


# a word said again after a hesitation or a search for the word ("Put the, um, the …", "switch on
# the, what's it called, the …"): the sentence goes on
_DETERMINER = r"(?:the|a|an|my|your|that|this)"
_HESITATION = re.compile(
    r"\b" + _DETERMINER + r"\s*(?:,|\.{2,}|…|—|-)\s*"
    r"(?:um+|uh+|erm+|er+|uhm+|hmm+|oh|you know|what's (?:it|that|the word) called|what's the word"
    r"|what do you call (?:it|that|them)|what do they call (?:it|that)|whatsit|whatchamacallit|thingy)"
    r"\s*(?:,|\.{2,}|…|—|-)\s*(" + _DETERMINER + r")\b"
    r"|\b(" + _DETERMINER + r")\s*(?:\.{2,}|…)\s*\2\b", re.IGNORECASE)  # "put the... the picture thing on"


# ("if you'd be good enough to put a video call through to him", text test v63)
_SO_KIND_AS_TO = re.compile(r"(?<!\bwonder )(?<!\bwondering )(?<!\bwondered )"  # "I wonder if you'd …": a request
                            r"\bif you(?:'d| would) be (?:so |ever so )?(?:kind|good) (?:enough (?:as )?|as )to\b",
                            re.IGNORECASE)
# Who wants the robot there, after "… is where": "I need you", "you should be" (`clause_kind`)
WANTED_THERE = (r"(?:(?:i|we)(?:'d| would)? (?:really )?(?:want|need|like) you\b"
                r"|you (?:should|ought to|need to|want to|belong)\b)")
_THATS_WHERE = re.compile(r"\b((?:the|my|your) \w+(?: \w+)?)\s*(?:,|—|-)\s*that(?:'s| is) where\b"
                          r"(?= " + WANTED_THERE + ")", re.IGNORECASE)

# A list's heading: "three little jobs for you: the hallway, then …", "Two things. …" (each is asked).
LIST_INTRO = re.compile(r"^(?:(?:a few|a couple of|two|three|four|some) )(?:little |small |more )?"
                        r"(?:things|jobs|tasks|errands)(?: for you| to do)?$"
                        # a heading for where to go instead: "Reroute: front door, …" (text test v54)
                        r"|^(?:reroute|redirect|new destination"
                        r"|(?:a )?new plan|change of plans?|plan b"  # "ok new plan, …" (text v68)
                        # "Let's do this: go to the kitchen, …" (text test v122 made it a step)
                        r"|let'?s do this|here'?s the plan|here'?s what (?:i want|we(?:'ll| will) do|to do))$",
                        re.IGNORECASE)

# Vague words that end a list of requests ("…, and turn the projector on and stuff"): no step
VAGUE = re.compile(r"^(?:stuff|things|everything|whatever|all that|and so on|so on|that sort of thing|etc)$",
                   re.IGNORECASE)
