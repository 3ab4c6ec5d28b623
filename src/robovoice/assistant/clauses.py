"""An utterance cut into clauses (`intent.read_request` reads each): at sentence ends, commas,
dashes and the conjunctions that join requests, keeping together what is one request ("go and
charge", "be a dear and pop in") and one name ("Dr. Weber", "my son, Ben")."""

from __future__ import annotations

import re

from robovoice.assistant.lexicon import IMPERATIVES, RELATIONS

# Sentence ends, commas/semicolons, and the conjunctions that join requests.
_SPLIT = re.compile(  # "Dr. Weber" is one name, not two sentences
    r"(?<!\bdr)(?<!\bmr)(?<!\bmrs)(?<!\bms)(?<!\bst)(?<!\bprof)[.!?;\u2026]+\s*"
    r"|,\s*(?:and then\s+|and after that\s+)?"  # ", and then home to the dock": no clause "and" (text test v63)
    r"|\s+(?:and then|and after that|and afterwards|after that|then|and also|and|but)\s+"
    r"|\s+[-\u2013\u2014]+\s+"  # "go to the bedroom - sorry, no, the living room"
    r"|:\s+"  # "three things: go into the lounge, …" (not a time: "half 3:30")
    # "forget that I go myself": a transcript that lost the comma after the take-back (audio test v117)
    r"|(?<=\bforget that)\s+(?=(?:i|i'll|i will|we|we'll)\s+(?!said\b|asked\b))"
    # "go to the bathroom before that, switch …": a transcript that lost the full stop
    r"|(?<!\bbut)(?<!\band)\s+(?=before (?:that|then)\s*(?:[,.!?]|$))"
    # "Call Ben, but before that turn on the projector" (text test v56); not "before that show starts"
    r"|(?<=\bbefore that)\s+(?=(?:" + "|".join(sorted(IMPERATIVES))
    + r")\s+(?:the|my|your|it|that|this|me|him|her|them|us|on|off|up|down|over|to|into|a|an)\b"
    r"|(?:the |your )?(?:projector|telly|tv|screen) (?:on|off)\b)",  # "… but before that projector on" (v125)
    re.IGNORECASE,
)
_LEADING = re.compile(r"^(?:and then|and after that|and afterwards|after that|then|and|but|also)\s+", re.IGNORECASE)
# "…, and once that's done take yourself off for a charge": the step before, done, then this one
# (… "and after you've done that go to …": not a step "do that" put first)
_DONE_THEN = re.compile(r"^(?:once|when|as soon as|after) (?:(?:that|this|it)(?:'s| is| has)(?: been)? "
                        # "… switch on the projector, and once it's warmed up call Anna" (text test v55)
                        r"(?:done|finished|over|sorted|warmed up|ready|on|running|up|going)"
                        # "…, and when you're done with that get yourself back on the charger" (text test v58)
                        r"|you(?:'re| are|'ve| have)? (?:all )?(?:done|finished)"
                        r"(?: with (?:that|this|it|them|her|him)| (?:that|it)(?!\s+(?:call|with)\b)| there| here"
                        r"| in there)?)"
                        # (said alone before a comma: "…, and when that's done, make your way …", text test v63)
                        r"(?:\s+(?!(?:with|that|this|it|them|there|here|in)\b)|$)", re.IGNORECASE)
# the robot named when the speaker passes a request on: "tell it to …", "ask the machine not to …"
_TELL_IT = r"(?:tell|ask) (?:it|the robot|the machine|jarvis)"
# "Mrs Pritchard asked me to get you to call Clara": a request passed on through the speaker, the
# robot's to do now (text test v58); its words are the request's own
_RELAYED = re.compile(r"^(?:(?!(?:i|we|you|it|nobody|no one|did|does|do|has|if|when|once)\b)(?:\w+\.? )?\w+ "
                      r"(?:asked|told|wants|wanted|would like|'d like) me to "
                      r"(?:(?:get|ask|tell) you to|have you)"
                      # … or by someone else in the room: "tell it to go to the bedroom" (text test v61)
                      rf"|(?:(?:please|kindly|just|go on) )?{_TELL_IT} to"
                      # … or what they say to do now: "Nenek says hang up the call now" (text test v113)
                      r"|(?!(?:i|it|that|this)\b)(?:\w+ )?\w+ says(?=\s+(?:" + "|".join(sorted(IMPERATIVES))
                      + r")\b[^.!?]*\b(?:now|please|right away|straight away)\b))"
                      r"\s+(?=\w)",
                      re.IGNORECASE)
# "tell the machine not to go in the kitchen": the same, not wanted (text test v68)
_RELAYED_NOT = re.compile(rf"^(?:(?:please|kindly|just) )?{_TELL_IT} not to\s+(?=\w)", re.IGNORECASE)
# "call her and, uh, then …": a conjunction left at the end by the comma after it (not at the
# very end: "Hey Jarvis, go and" was cut off)
_TRAILING = re.compile(r"\s+(?:and then|and)$", re.IGNORECASE)


# "go and charge", "come and find me": one request whose verb follows the "and", not two
# "turn round and go back to your dock": the way it goes, no call-off of its own (text tests v24, v25:
# offered the cancel for "turn round", the model cancelled nothing and never drove)
_TURN_AND = re.compile(r"\bturn (?:round|around|back)\s+and\s+(?=(?:go|head|come|drive|make|get)\b)", re.IGNORECASE)
# "nice and big", "good and loud": one manner, not two steps (text test v51)
_NICE_AND = re.compile(r"\b(nice|good|lovely)\s+and\s+(?=(?:big|bright|loud|large|clear|close|wide|sharp)\b)",
                       re.IGNORECASE)
# "come back and wait in the hallway": where to wait is where to go, one request (text test v60: the
# robot's stop ran for its "wait")
_AND_WAIT = re.compile(r"\b((?:go|come|head|get|pop|nip) (?:back|over|round|through|down|up))\s+and\s+"
                       r"(?=(?:wait|stay|sit|park)\s+(?:in|at|by|near|inside|outside|beside)\b)", re.IGNORECASE)
# "…, away and wait by the front door": Scots for "go and" (text test v51: the robot's stop ran)
_AWAY_AND = re.compile(r"(?:(?<=^)|(?<=[,.;!?] ))away\s+and\s+(?=\w)", re.IGNORECASE)
_GO_AND = re.compile(r"\b(go|come|try|pop|run|hurry)\s+and\s+(?!then\b|after\b|also\b|afterwards\b)", re.IGNORECASE)


# "would you be a dear and pop into the kitchen", "please be so kind as to come to the living room"
# (text test v82): courtesy around one request
# (any one or two words: "be a doll and call …", heard "be a go and call …": audio test v84)
_BE_A_DEAR = re.compile(r"\bbe (?:(?:a|an) (?:\w+ )?\w+|good) and\s+|"
                        r"\bbe (?:so kind as|kind enough|good enough|so good as) to\s+",
                        re.IGNORECASE)


# "ring my son, Ben": the name says who the relation is, not another thing asked
_APPOSITIVE = re.compile(r"\b((?:my|your|our) (?:" + "|".join(sorted(RELATIONS)) + r"))\s*,\s*(?=(?-i:[A-Z][a-z]+)\b)",
                         re.IGNORECASE)


# "Could ye head through to the bathroom", "will youse ring Ben": you, as said in Ireland,
# Scotland and the north of England (text test v23)
_YOU = re.compile(r"\b(?:ye|youse|yous|ya)\b", re.IGNORECASE)  # "off to bed with ya" (text test v55)


# "and after that call, Clara": speech-to-text's comma between a call and whom (audio test v14)
_CALL_COMMA = re.compile(r"(?<!\bthe )(?<!\ba )(?<!\bvideo )\b((?i:call|ring|phone))\s*,\s+(?=[A-Z][a-z]+\b)")


# "before you go charge can you switch the projector off": the comma speech-to-text (or a
# hurried typist) left out between the step said first and the request (text test v39)
# … or before a command ("before you call Clara switch on the projector", audio test v58), also after
# "you've" ("after you've been to the kitchen come back …")
_ORDER_THEN_ASK = re.compile(r"^(?!\w+ you've (?:done|finished)\b)"  # "after you've done that …": `_DONE_THEN`
                             r"((?:before|after|once) you(?:'ve)? (?:\w+ ){0,6}?\w+)\s+"
                             r"(?=(?:can|could|would|will) you \w"
                             r"|(?<!^before you )(?<!^after you )(?<!^once you )"
                             # (not a noun: "after you finish this call with Anna, …")
                             r"(?<!\bthis )(?<!\bthe )(?<!\bthat )(?<!\ba )(?<!\bmy )(?<!\byour )(?<!\bvideo )"
                             r"(?:switch|turn|put|call|ring|phone|give|go|head|come|drive) "
                             r"[a-z]\w*\b)", re.IGNORECASE)  # and any word after it


# "once it's up and running, ring Anna": one state, no "and" between two clauses (text test v64)
_UP_AND = re.compile(r"\bup and (?:running|going)\b", re.IGNORECASE)


# "is it just on and off?": one way of working, not two switches (text test v68)
_ON_AND_OFF = re.compile(r"\b(on|off) and (?!\1\b)(on|off)\b", re.IGNORECASE)


def split_clauses(text: str) -> list[str]:
    text = _ON_AND_OFF.sub(r"\1-and-\2", _UP_AND.sub("up", text))
    text = _ORDER_THEN_ASK.sub(r"\1, ", _CALL_COMMA.sub(r"\1 ", _YOU.sub("you", text.strip())))
    text = _AND_WAIT.sub(r"\1 ", _NICE_AND.sub(r"\1-and-", _TURN_AND.sub("", _AWAY_AND.sub("go and ", text))))
    text = _APPOSITIVE.sub(r"\1 ", _GO_AND.sub(r"\1 ", _BE_A_DEAR.sub("", text)))
    said = (_done_then(_LEADING.sub("", p.strip(" ,.;:!?-\"'")), i) for i, p in enumerate(_SPLIT.split(text)))
    parts = [p for p in (_RELAYED.sub("", _RELAYED_NOT.sub("don't ", p)) for p in said) if p]
    return [_TRAILING.sub("", p) for p in parts[:-1]] + parts[-1:]


def _done_then(part: str, at: int) -> str:
    """`part` without its "once that's done": said first and alone, it is about something under
    way, a condition (`intent.read_request`), and stays."""
    rest = _DONE_THEN.sub("", part)
    return part if at == 0 and not rest else rest
