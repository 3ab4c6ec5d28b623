"""Does an action fit what was asked? The second half of the check before acting.

`gate` asks *whether* the person asked for an action now; this asks *which*. A small model
beside a real request sometimes picks a tool nobody asked for: "go and get yourself charged
up" switched the projector on, "go to the front door and check who has come" called Anna.
A manifest tool may declare the words a request for it uses (``voice.words``: "call",
"ring", "hang up"); the call then fits only when one of the request's clauses says one of
those words, a word of the tool's own name, or a word of one of the call's text arguments
("Anna", "kitchen"). Words are compared by their stems ("charged" is "charge", "rings" is
"ring"); a declared phrase ("hang up") must appear in that order.

A tool that declares no words is not checked: nothing is known about how people ask for it.
An answer to the robot's own question ("Shall I call Anna?" - "Yes, please.") is read with
the conversation before it, which says what the "yes" is for.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Collection, Iterable, Mapping, Sequence
from typing import Any

from robovoice.assistant.lexicon import BESIDE, FILLER, words
from robovoice.assistant.reading import ClauseKind, Intent

_SHORT_FORMS = {"dr": "doctor", "doc": "doctor", "mr": "mister", "mrs": "missus", "neighbor": "neighbour"}
_BACK_REFERENCE = frozenset({"it", "them", "that", "one", "this"})
# "this" and "that" before a noun name it ("stop this call": no back reference, text test v49);
# before these, or last, they point back ("turn that off", "this thing")
_POINTS_ON = frozenset({"thing", "things", "stuff", "one", "on", "off", "up", "down", "out", "in", "back", "for",
                        "to", "please", "now", "again", "over", "round", "around", "too", "as", "at", "with", "and",
                        "then", "so", "right", "first", "instead"})


# "The projector's been humming all afternoon. Off, please.": a bare "on" or "off" is about what was named (text v65)
_BARE_SWITCH = frozenset({"on", "off", "please", "now", "then", "again", "thanks"})


def refers_back(text: str) -> bool:
    said = words(text)
    if said and set(said) <= _BARE_SWITCH and set(said) & {"on", "off"}:
        return True
    # (an "it" that is the subject names nothing asked: "go and check who it is", text test v105)
    return any(w in _BACK_REFERENCE and (w not in ("this", "that") or i + 1 == len(said) or said[i + 1] in _POINTS_ON)
               and not (w == "it" and said[i + 1:i + 2] in (["is"], ["was"]))
               for i, w in enumerate(said))


def usual(names: Iterable[str]) -> set[str]:
    """The words as said aloud, without a possessive: "dr" is "doctor", "son's" is "son" (and a
    "neighbor" the same as a "neighbour")."""
    return {_SHORT_FORMS.get(w.removesuffix("'s"), w.removesuffix("'s")) for w in names}


# Words of a tool's name that say nothing about what it acts on.
GENERIC_NAME_WORDS = frozenset({"set", "get", "start", "end", "to", "power", "state", "robot", "the", "on", "off"})

_SUFFIXES = ("ing", "ed", "es", "er", "s")


def stem(word: str) -> str:
    """A word without its ending: "charging", "charged", "charge" → "charg"; "plugged" → "plug"."""
    word = word.lower().removesuffix("'s").replace("'", "")
    for suffix in _SUFFIXES:
        if word.endswith(suffix) and len(word) - len(suffix) >= 2:
            word = word[: -len(suffix)]
            if len(word) > 2 and word[-1] == word[-2] and word[-1] not in "lsz":
                word = word[:-1]  # "plugg" → "plug", but "call" stays
            break
    return word.removesuffix("e") if len(word) > 2 and word != "bye" else word  # "bye" is not "by"


def _stems(text: str) -> list[str]:
    return [stem(w) for w in words(text)]


def _at(clause: Sequence[str], phrase: Sequence[str]) -> list[int]:
    """Where the clause's stems contain the phrase's, in order and next to each other."""
    n = len(phrase)
    return [i for i in range(len(clause) - n + 1) if list(clause[i:i + n]) == list(phrase)] if n else []


def _says(clause: Sequence[str], phrase: Sequence[str]) -> bool:
    return bool(_at(clause, phrase))


def subject_words(name: str) -> set[str]:
    """The words of a tool's name that say what it acts on: "start_video_call" → video, call."""
    return set(words(name.replace("_", " "))) - GENERIC_NAME_WORDS


def vocabulary(name: str, declared: Iterable[str], arguments: Mapping[str, Any]) -> list[list[str]]:
    """The phrases (as stems) any of which makes a request clause fit this call."""
    own = sorted(subject_words(name))
    values = [w for value in arguments.values() if isinstance(value, str) for w in words(value)]
    said_aloud = sorted(usual(values) - set(values))  # "Dr. Weber": "doctor"
    return [[stem(w)] for w in own + values + said_aloud] + [p for phrase in declared for p in _kinds_of(phrase)]


# A word searched for ("the picture thing", "the picture box", "the picture machine"): any one of
# these after a declared word is the same thing (text test v97: "Stick the picture box on" was refused)
_GENERIC = ("thing", "thingy", "box", "machine", "gadget", "contraption", "doodah", "whatsit", "one")


def _kinds_of(phrase: str) -> list[list[str]]:
    """The phrase as stems, and, where it ends on a word like "thing", each of those words in its place."""
    said = _stems(phrase)
    if len(said) < 2 or said[-1] not in {stem(g) for g in _GENERIC}:
        return [said]
    return [said, *([*said[:-1], stem(g)] for g in _GENERIC if stem(g) != said[-1])]


def names(sentence: str, name: str, arguments: Mapping[str, Any], declared: Sequence[str] = ()) -> bool:
    """The sentence names this call: a word of the tool's name or of its text arguments ("The
    video call with Ben has started." names start_video_call(contact=Ben)), or one of the tool's
    `declared` words ("screen" for the projector)."""
    said = _stems(sentence)
    return any(_says(said, phrase) for phrase in vocabulary(name, declared, arguments))


# The courtesy a request may open with, before its verb: "could you please hang up the call"
_COURTESY = re.compile(r"^(?:(?:so|please|kindly|just|now|could|would|can|will|you|go ahead and|let'?s|let us)"
                       r"(?!\w)[\s,]*)+"  # "let's wrap up the call with Anna": the end's words open it (text v81)
                       # "… be kind enough to call Ben": no "enough" of the stop's words
                       r"|\bbe (?:so |ever so )?(?:kind|good) (?:enough )?(?:as )?(?=to\b)", re.IGNORECASE)


def _request_stems(intent: Intent, said: Collection[str], kinds: Collection[ClauseKind] = (ClauseKind.REQUEST,),
                   pooled: bool = True, beside: bool = False) -> list[list[str]]:
    requests = [c for c in intent.clauses if c.kind in kinds]
    # (`beside`, for a call with no value of its own: "keep the photo next to the projector" is no switch)
    clauses = [_stems(_COURTESY.sub("", FILLER.sub("", BESIDE.sub("", c.text.strip()) if beside else c.text.strip())))
               for c in requests]  # "ok wrap up …"
    # (an ability question's "it" is not looked up: "If Ben rings, could you answer it?" is
    # not a question about ringing him, and the robot's "yes" must be to what it names)
    if pooled and ClauseKind.REQUEST in kinds and any(refers_back(c.text) for c in requests):
        # "the thing that throws pictures on the wall... turn it off": what "it" is was said before
        clauses += [_stems(c.text) for c in intent.clauses]
    if intent.answering:
        clauses.append([stem(w) for w in said])  # "Yes, please." to "Shall I call Anna?"
    return clauses


def fits(intent: Intent, name: str, declared: Sequence[str], arguments: Mapping[str, Any],
         said: Collection[str] = (), rivals: Iterable[Sequence[str]] = (), aliases: Iterable[str] = (),
         elsewhere: Collection[str] = (), kinds: Collection[ClauseKind] = (ClauseKind.REQUEST,),
         pooled: bool = True) -> bool:
    """Some request clause (a clause of `kinds`) says a word of this call's vocabulary (True when none is declared;
    `aliases`: the words of its values' other names, "hall" for the hallway), and does not open
    with a rival tool's words (`rivals`: the declared words of each tool acting on the same
    thing) while this call's come later or are shorter: "hang up the call" and "ring off from
    Anna" ask to end a call, not to start one. `pooled`: a request that points back ("turn it
    off") is read with every clause (False for the robot's stop and cancel: "That's enough of
    that, turn it off. The call, I mean." is no stop, text test v65).
    A call without words for its arguments (a stop, a yes/no) does not fit a clause whose
    words for it only come before what another tool acts on (`elsewhere`: the other tools'
    `subject_words`): "you can stop the call now" is not the robot's stop."""
    if not declared:
        return True
    phrases = vocabulary(name, declared, arguments) + [[stem(w)] for w in aliases]
    others = [_stems(phrase) for phrase in itertools.chain.from_iterable(rivals)]
    aimed = {stem(w) for w in elsewhere} - {stem(w) for w in subject_words(name)}
    if aimed_at := any(isinstance(value, str) for value in arguments.values()):
        aimed = set()  # a place or a person says what it acts on
    acts = vocabulary(name, declared, {})  # its own words: a message for somebody fits only through them
    # what a request may open with for it: its declared words and values, not a word of its name
    # alone ("Call the plumber" opens with the call's verb, not end_video_call's noun)
    openings = phrases[len(subject_words(name)):]
    for clause in _request_stems(intent, said, kinds, pooled, beside=not aimed_at):
        own_only = _message(clause) or _handles(clause)
        if not any(_says_for_it(clause, phrase, aimed) for phrase in (acts if own_only else phrases)):
            continue
        mine = _longest_opening(clause, openings)
        if clause and [clause[0]] in phrases[:len(phrases) - len(openings)] and (
                then := _longest_opening(clause[1:], openings)):
            mine = max(mine, then + 1)  # "call end karo" (Hindi's word order): the call's noun, then its verb
        if _longest_opening(clause, others) > mine:
            continue  # "ring off from Anna" opens with the end's "ring off", not the call's "ring"
        return True
    return False


# "Tell Anna I'm feeling better" (during a call with her): a message for somebody names them
# without asking to act on them; only the action's own words make it fit. (A goodbye such as
# "tell Anna cheerio", text test v23's, is no request at all: `lexicon.FAREWELL`.)
_MESSAGE_VERBS = frozenset(stem(w) for w in ("tell", "ask", "remind", "let", "wish", "say", "send"))


def _message(clause: Sequence[str]) -> bool:
    if not clause or clause[0] not in _MESSAGE_VERBS:
        return False
    return clause[0] != "let" or "know" in clause[1:4]  # "let Anna know …", not "let's see if you can …"


# "Open the door", "lock the back door", "clean the kitchen": a verb done with hands to what
# it names, which asks nobody to go there (text test v43: "open the door" drove to the front
# door). Only the action's own words make such a clause fit ("close the call" ends it).
_HANDS_ON = frozenset(stem(w) for w in (
    "open", "close", "shut", "lock", "unlock", "bolt", "latch", "clean", "tidy", "hoover", "vacuum", "mop",
    "sweep", "dust", "scrub", "wash", "paint", "fix", "mend", "repair"))


def _handles(clause: Sequence[str]) -> bool:
    return bool(clause) and clause[0] in _HANDS_ON


_DETERMINERS = frozenset(stem(w) for w in ("the", "that", "this", "your", "my", "a", "an"))
# a verb's helper after the thing, no name of another ("the projector can go off": "can" is not "cancel")
_MODALS = frozenset(stem(w) for w in ("can", "could", "may", "might", "must", "should", "will", "would", "shall",
                                      "is", "was", "has", "had"))


def _says_for_it(clause: Sequence[str], phrase: Sequence[str], aimed: Collection[str]) -> bool:
    """The clause says the phrase at least once not right before (after a "the", a "that") a
    word naming something in `aimed`: "stop the call", "plug the projector in", "stop the
    project" (a misheard "pop the projector on") say it only for another tool."""
    for i in _at(clause, phrase):
        j = i + len(phrase)
        while j < len(clause) and clause[j] in _DETERMINERS:
            j += 1
        if j >= len(clause) or clause[j] in _MODALS or not _names(clause[j], aimed):
            return True
    return False


def _opens(clause: Sequence[str], phrase: Sequence[str]) -> bool:
    return bool(phrase) and list(clause[:len(phrase)]) == list(phrase)


def _longest_opening(clause: Sequence[str], phrases: Iterable[Sequence[str]]) -> int:
    """How many words of the longest of `phrases` the clause opens with (0: none)."""
    return max((len(p) for p in phrases if _opens(clause, p)), default=0)


def fitting_tools(intent: Intent, declared: Mapping[str, Sequence[str]], but: str) -> list[str]:
    """The tools other than `but` whose declared words (or name) a request clause says, sorted:
    what the person may have meant instead."""
    return sorted(name for name, phrases in declared.items()
                  if name != but and phrases and fits(intent, name, phrases, {}))


def claimed_elsewhere(intent: Intent, name: str, arguments: Mapping[str, Any],
                      declared: Mapping[str, Sequence[str]], values: Mapping[str, Collection[str]],
                      said: Collection[str] = ()) -> bool:
    """Every request clause that says this call's words says only words another tool declares too, beside
    a value only that tool lists (`values`: each tool's stems naming its listed values, `listed_names`):
    "get Ben up on the screen" is the call's "screen", not the projector's (text test v25)."""
    own = vocabulary(name, declared.get(name, ()), arguments)
    theirs = {tool: [_stems(p) for p in phrases] for tool, phrases in declared.items() if tool != name}
    claimed = False
    everyone = {stem(w) for w in [*intent.words(), *said]}  # "Put her on the screen, Clara I mean" (text v127)
    for clause in _request_stems(intent, said):
        hits = [phrase for phrase in own if _says(clause, phrase)]
        if not hits:
            continue
        heard = set(clause) | {stem(w) for w in usual(clause)} | (everyone if {"her", "him"} & set(clause) else set())
        if not any(all(h in stems for h in hits) and heard & set(values.get(tool, ()))
                   for tool, stems in theirs.items()):
            return False  # this clause asks for this call in its own words
        claimed = True
    return claimed


def value_owner(name: str, parameters: Mapping[str, Any], arguments: Mapping[str, Any],
                values: Mapping[str, Collection[str]]) -> str | None:
    """The other tool one of whose listed values this call's argument is, where this tool lists
    no such value: a drive to "Ben" (text test v26, "get Ben up on it") is a call's argument."""
    for arg, value in arguments.items():
        said = {stem(w) for w in usual(words(value))} - _FUNCTION_WORDS if isinstance(value, str) else set()
        if not said or not unlisted(parameters, {arg: value}):
            continue
        owner = next((tool for tool, names in values.items() if tool != name and said <= set(names)), None)
        if owner is not None:
            return owner
    return None


def listed_names(description: str, parameters: Mapping[str, Any]) -> set[str]:
    """The stems that name the values a tool lists, with their other names: "Anna (daughter)"."""
    return {n for found in listed(parameters).values() for v in found for n in _names_for(v, description)}


# --- arguments somebody said -------------------------------------------------------------------

_FUNCTION_WORDS = frozenset({"the", "a", "an", "of", "my", "your", "to", "in", "on", "at", "and"})


def glosses(value: str, description: str) -> list[str]:
    """The other names a description gives `value` in brackets right after it: "Anna
    (daughter)" -> ["daughter"], "bathroom (loo, toilet)" -> ["loo", "toilet"]."""
    gloss = re.search(re.escape(value) + r"\s*\(([^)]*)\)", description, re.IGNORECASE)
    return [g.strip() for g in gloss.group(1).split(",") if g.strip()] if gloss is not None else []


def _names_for(value: str, description: str, every_word: bool = False) -> set[str]:
    """The stems that name `value`: its own words as said aloud ("doctor" for "Dr."), and its
    glosses' words — of a gloss of several words, its last only ("family doctor": "doctor";
    "ring my family" named Dr. Weber, text test v47), unless `every_word` (a word that may
    belong to it: "front" of "front room" makes "front" no sure name of the front door)."""
    own = usual(words(value))
    glossed = {w for g in glosses(value, description) for w in (words(g) if every_word else words(g)[-1:])}
    return {stem(w) for w in (own | glossed) - _FUNCTION_WORDS}


def unsaid(description: str, parameters: Mapping[str, Any], arguments: Mapping[str, Any],
           heard: Iterable[str]) -> list[str]:
    """The values of the call's listed arguments (a schema property with ``enum`` or
    ``examples``: places, contacts) that nobody named in what was said (`heard`: the
    conversation's words and this utterance's): "get car on a video call" became Anna, "ring my
    sun" Dr. Weber, a garbled "Go man." the kitchen. A stem that begins another counts ("bed"
    names the bedroom), unless it is part of another listed value too ("that room" names none
    of the living room, the bedroom, the bathroom); a value that is not listed counts as named
    when all its words were said ("the front room"); free text (a message) is not checked."""
    said = {stem(w) for w in usual(heard)}
    choices = listed(parameters)
    missing = []
    for name, value in arguments.items():
        if name not in choices or not isinstance(value, str) or not value.strip():
            continue
        names = _names_for(value, description)
        if value.lower() not in {v.lower() for v in choices[name]} and names and names <= said:
            continue  # the person's own name for it ("the front room"): the robot resolves it or says it cannot
        if any(said_whole(g, said) for g in glosses(value, description)):
            continue  # "the front room": a gloss said whole, though "front" and "room" name others too
        others = [n for v in choices[name] if v.lower() != value.lower() for n in _names_for(v, description, True)]
        if names and not any(_names(s, names) and not any(s in n for n in others) for s in said):
            missing.append(value)
    return missing


def named_whole(value: str, description: str, heard: Iterable[str]) -> bool:
    """`value`, or one of its other names, said whole in `heard` ("the hall", "living room"),
    not only begun ("washing" does not name the washroom)."""
    said = {stem(w) for w in usual(heard)}
    return any(said_whole(p, said) for p in (value, *glosses(value, description)))


def said_whole(phrase: str, said: set[str]) -> bool:
    stems = {stem(w) for w in usual(words(phrase))} - _FUNCTION_WORDS
    return bool(stems) and stems <= said


def listed(parameters: Mapping[str, Any]) -> dict[str, list[str]]:
    """The arguments whose schema lists their values (``enum`` or ``examples``), with the values."""
    found: dict[str, list[str]] = {}
    for name, schema in (parameters.get("properties") or {}).items():
        values = (schema.get("enum") or schema.get("examples")) if isinstance(schema, Mapping) else None
        if isinstance(values, list) and values:
            found[name] = [str(v) for v in values]
    return found


def unlisted(parameters: Mapping[str, Any], arguments: Mapping[str, Any]) -> bool:
    """Some argument names none of the values its schema lists ("Gunner", the contacts being
    Anna, Ben, Clara and Dr. Weber; "Weber" names one)."""
    values = {arg: [w for value in found for w in words(value)] for arg, found in listed(parameters).items()}
    return any(isinstance(value, str) and not named_in(values[arg], words(value))
               for arg, value in arguments.items() if arg in values)


def named_in(values: Iterable[str], heard: Iterable[str]) -> bool:
    """Some word heard names one of the words of `values` (by stem, or a stem that begins it:
    "the hall" names the hallway)."""
    names = {stem(w) for w in usual(values)}
    return any(_names(stem(w), names) for w in usual(heard))


def _names(said: str, names: Collection[str]) -> bool:
    """The said stem is one of `names`, or (3 letters or more) begins one."""
    return any(n == said or (len(said) >= 3 and n.startswith(said)) for n in names)


# "Turn that off... turn it off." with nothing named anywhere in the conversation: the one thing
# the robot's tools can switch (text test v39). Off only: switching on what nobody named is a guess.
_SWITCH_IT_OFF = re.compile(r"^(?:(?:turn|switch|shut|put|flip|click|knock) (?:it|that|this)(?: thing)? off"
                            r"|(?:turn|switch|shut) off (?:it|that|this))(?: (?:now|please|then|again))*$",
                            re.IGNORECASE)


def switches_the_one_thing_off(intent: Intent, name: str, arguments: Mapping[str, Any], said: Collection[str],
                               switches: Mapping[str, Mapping[str, Any]]) -> bool:
    """Every clause asks to switch "it" off (or for something else by name), nothing said before
    names what "it" is, and this call switches off the only thing the robot can switch:
    `switches` holds each actuation tool's parameters."""
    flags = {tool: _flag(parameters) for tool, parameters in switches.items()}
    flag = flags.get(name)
    if flag is None or arguments.get(flag) is not False or sum(f is not None for f in flags.values()) != 1:
        return False
    asked = [_COURTESY.sub("", c.text.strip()) for c in intent.clauses]
    return not said and any(_SWITCH_IT_OFF.match(a) for a in asked) and all(
        c.kind is ClauseKind.REQUEST for c in intent.clauses)


def _flag(parameters: Mapping[str, Any]) -> str | None:
    """The one argument of a tool that takes a single yes/no ("on")."""
    properties = parameters.get("properties") or {}
    flags = [arg for arg, schema in properties.items()
             if isinstance(schema, Mapping) and schema.get("type") == "boolean"]
    return flags[0] if len(properties) == 1 and len(flags) == 1 else None
