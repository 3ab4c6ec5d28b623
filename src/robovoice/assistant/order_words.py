"""The order words `intent.read_request` reads between clauses: "first", "before that", "before
you …", "after that", "once you've found him …", a bare "wait" (a pause), "go on" (urging), and
a time that is not now said after a request ("…, but not at the moment")."""

from __future__ import annotations

import re
from collections.abc import Iterable

from robovoice.assistant.lexicon import FILLER, IMPERATIVES, LATER_ONLY, words
from robovoice.assistant.reading import Clause, ClauseKind

# "…, and once you've got her, …": the step before done, then what follows
HIM_THEN = re.compile(r"^\s+(?:him|her|them|it)\s+(\w.*)$", re.IGNORECASE)
# (… or "after you've spoken to her, …": text test v94)
BACK_ONLY = re.compile(r"^\s*(?:with |to )?(?:him|her|them|it|that|this|through)?\W*$", re.IGNORECASE)
# A place or a person with an order word and nothing else is a step: "first the kitchen, then …"
ORDERED_FRAGMENT = re.compile(r"^(?!first things first$)(?:first(?:ly)?,? (?!of all$|thing$|off$|up$)(?:to |into )?"
                              r"(?:the |my |your )?"
                              r"\w+(?: \w+)?|(?:the |my |your )?\w+(?: \w+)? first"
                              r"(?: to (?!be\b)\w+(?: \w+){0,5})?)$",  # "… first to check the parcel" (text v115)
                              re.IGNORECASE)
FIRST_ALONE = re.compile(r"^(?:first(?:ly)?(?: of all| things first| thing| off| up)?|to (?:start|begin) with)$",
                         re.IGNORECASE)  # "First thing, put off that projector" (text test v95)
# "…, and switch the projector on before all that" (text test v95): the step goes first, as "… first" does
BEFORE_ALL = re.compile(r"\bbefore (?:all (?:of )?(?:that|this)|any of (?:that|this)|anything else"
                        r"|everything(?: else)?)\W*$", re.IGNORECASE)
# not "after lunch": no request; "thereafter" (v49), "after which", "followed by" (v50), "straight after" (audio v41),
# "from there" (v90)
AFTER = re.compile(r"^(?:(?:(?:straight|right|immediately|directly) )?after(?:wards| that| this| which)?|thereafter"
                   r"|followed by|from there)\b(?!\s+you\b)[\s,]*", re.IGNORECASE)
# "Tell me that first": the question said before it is the step, and it is first already.
THAT_FIRST = re.compile(r"^(?:tell me|let me know)(?: that| it)?(?: first| now| please)*$", re.IGNORECASE)
# Order words: "before that, …" / "before you ring Clara, …" / "…, but first …", "… first".
# "… and before all that, come to the living room" (text test v90)
BEFORE_THAT = re.compile(r"^before(?: (?:that|then|you do that|doing that|you do|you go|anything else"
                         r"|(?:all|any) (?:of )?(?:that|this)|everything(?: else)?))?(?:,? (?:though|tho))?$",
                         re.IGNORECASE)  # (text v112)
# (a bare "before": "call Ben, but before, go to kitchen, please", audio test v116)
_BEFORE_YOU = re.compile(r"^before you (\w+.*)$", re.IGNORECASE)
URGE = re.compile(r"^(?:(?:ah|oh|aw|och|come),? )?go on(?: then| now| so)?$", re.IGNORECASE)  # "go on so" (v59)
PAUSE = re.compile(r"^(?:(?:oh|ah|um|er|erm|eh),? )*(?:wait|hang on|hold on)(?:,? (?:wait|hang on|hold on))*$",
                   re.IGNORECASE)  # "oh wait", "wait wait"
# "ring Anna, oh wait, no, …": only a bare "no" or "wait" said since, which a step put first leaves
# standing; "no, forget it" took the call back for good
_BARE_NO = re.compile(r"^(?:(?:oh|ah|um|er|erm|no|wait|sorry|actually|hmm|well) )*(?:no|wait|hang on|hold on|sorry)$",
                      re.IGNORECASE)
AFTER_YOU = re.compile(r"^(?:after|once|as soon as) you (?!(?:'|are|get|go there|arrive)\b)(\w+ \w.*)$", re.IGNORECASE)
FIRST = re.compile(r"\bfirst\b(?! (?:time|floor|thing|of all))", re.IGNORECASE)

# a time said before, held to (audio test v42: "after his lunch you can …, but not before")
# and a time that is not now, said after the request (text test v63: "…, but not at the moment, thank you")
NOT_BEFORE = re.compile(r"^(?:but |though )?(?:not (?:before|until then|till then|(?:just )?yet|(?:just |right )?now"
                        r"|at the moment|at present|this minute|today|tonight)|no sooner"
                        r"|hold off(?: on (?:that|it))?(?: (?:for )?(?:now|a (?:bit|moment|minute|sec(?:ond)?)))?)"
                        r"(?:,? (?:though|thanks|thank you|please|mind))*[\s.!]*$", re.IGNORECASE)
# "before calling Anna, …" (audio test v59): the same as "before you call Anna"
_BEFORE_DOING = re.compile(r"^before (\w+)ing\b(.*)$", re.IGNORECASE)


def before_you(bare: str) -> str | None:
    """The request said after "before you" or "before <verb>ing" ("call Anna" for "before calling
    Anna"), or None."""
    if you := _BEFORE_YOU.match(bare):  # "before you calls Clara" (Newfoundland, text test v95): "call"
        verb, rest = you.group(1).split(" ", 1) if " " in you.group(1) else (you.group(1), "")
        said = verb[:-1] if verb.lower().endswith("s") and verb[:-1].lower() in IMPERATIVES else verb
        return f"{said} {rest}".strip()
    # (with the thing it is done to, and nobody else doing it: "before going to bed I read")
    if (doing := _BEFORE_DOING.match(bare)) is None or not doing.group(2).strip() \
            or re.search(r"\b(?:i|we|he|she|they|you)\b", doing.group(2), re.IGNORECASE):
        return None
    stem = doing.group(1).lower()
    verb = next((v for v in (stem, stem + "e", stem[:-1]) if v in IMPERATIVES), None)  # ring, charge, put
    return None if verb is None else verb + doing.group(2)


def same_step(said: str, request: str) -> bool:
    """Whether `said` names again the step `request` asks for: "call him" after "Call Ben", "go
    there" after "go to the kitchen" (its verb, and nothing the request does not say but who or where)."""
    first, *rest = words(said) or [""]
    return words(request)[:1] == [first] and set(rest) - _BACK_WORDS <= set(words(request))


_BACK_WORDS = frozenset({"him", "her", "them", "it", "there", "that", "the", "a", "an"})


def only_paused(texts: Iterable[str]) -> bool:
    """Whether each of `texts` is only a "no" or a "wait" ("oh wait, no"): a request taken back
    that way is kept when the next says what to do before it."""
    return all(_BARE_NO.match(re.sub(r"[^\w']+", " ", text).strip()) for text in texts)


def paused(text: str) -> bool:
    """Whether `text` is only a pause between a request and what is said of it: a bare "no" or "wait"
    (`only_paused`), or nothing but fillers ("hmm", "actually", "oh")."""
    return only_paused([text]) or not FILLER.sub("", text).strip()


# the words of a time of day said alone ("…, later. Not now. Evening.")
_WHEN = frozenset({"in", "the", "this", "evening", "morning", "afternoon", "tonight", "night", "tomorrow", "later"})


def puts_off(said: str, after: Iterable[str]) -> bool:
    """Whether `said`, right after a request, holds it back: "…, but not yet", "hold off"; or a time
    alone with nothing said after it but more times (`after`: the clauses' words): "Anna call...
    later. Not now. Evening." (text test v112 rang Anna); not "Go to the kitchen. Later, call Ben.",
    where the time is the call's."""
    return bool(NOT_BEFORE.match(said.strip())) or (bool(LATER_ONLY.match(said.strip())) and all(
        NOT_BEFORE.match(a.strip()) or LATER_ONLY.match(a.strip()) or paused(a) or set(words(a)) <= _WHEN
        for a in after))


# a wait after a request, as part of it: "Go to hallway and wait little bit; after that, front door"
# (text test v129: "front door" was read as talk)
_AWHILE = re.compile(r"^(?:and |then )?(?:wait|stay)(?: there| here)?(?: for)?(?: a| one)?(?: little| wee| small)?"
                     r" (?:bit|while|moment|minute|second|sec)s?(?: there| here)?$", re.IGNORECASE)


def past_a_wait(clauses: list[Clause], at: int | None) -> int | None:
    """The clause at `at`, or the request before it where that is a wait a while after it."""
    if at and _AWHILE.match(FILLER.sub("", clauses[at].text).strip()) and clauses[at - 1].kind is ClauseKind.REQUEST:
        return at - 1
    return at
