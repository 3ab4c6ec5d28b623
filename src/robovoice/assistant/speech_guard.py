"""The last check before words reach the user: never speak or print raw tool-call syntax, nor
the model's own instructions read out (`ModelOnlyText`).

Backends turn calls written as text into real calls (`robovoice.llm.text_calls`), but a model
or server can still leak its syntax (a broken call, a format not recognised, control tokens).
Speaking "functions dot get battery state colon" to an older adult is worse than silence, so a
sentence that carries such syntax is dropped whole. Pure functions: the callers (speech output,
the chat printer) log what they drop.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Collection, Iterable, Sequence
from dataclasses import dataclass

from robovoice.assistant.events import ToolCalled, ToolReturned
from robovoice.assistant.fit import names
from robovoice.assistant.gate import NOT_REQUESTED, model_only_texts
from robovoice.assistant.prompt import STEP_HINTS, SYSTEM_PROMPT

_TOOL_SYNTAX = re.compile(
    r"</?tool_call>|</?tool_response>|</?function_call>|<function=|</function>"
    r"|\[/?TOOL_CALLS\]|\[/?TOOL_RESULTS\]|\[/?AVAILABLE_TOOLS\]"
    r"|<\|[A-Za-z_][\w-]*\|>"  # chat-template control tokens: <|im_start|>, <|python_tag|>, <|eot_id|>
    r"|<(?:start|end)_of_turn>"
    r"|</?think>"  # a reasoning model's thinking, passed through by a server without a reasoning parser
    r"|</?tools>"  # the tag Qwen2.5's template lists the tools in, copied out by the model
    r'|\{\s*"type"\s*:\s*"function"'  # a tool's definition read back
    r'|\{+\s*"name"\s*:'  # any object that opens with a name: a call, its arguments left out or not
    r"|```"  # a Markdown code fence (a coder model puts a call between two)
    r"|\b[a-z]+(?:_[a-z]+)+\b"  # an identifier: a tool's name read out ("did not ask for set_projector_power")
    r"|\bfunctions\.[A-Za-z_]\w*"  # chatml-function-calling's call head (not "functions." ending a sentence)
    r'|\{\s*"(?:name|function)"\s*:\s*"[^"]*"\s*,\s*"(?:arguments|parameters)"'  # a call as a JSON object
    r'|"(?:arguments|parameters)"\s*:\s*\{[^{}]*\}\s*,\s*"name"\s*:'  # ... with its keys the other way round
)


# The end-of-turn marker a server forgot to strip ends an answer that is otherwise fine: it is cut
# off, not a reason to drop the answer's last sentence.
_END_MARKERS = re.compile(r"(?:\s*(?:<\|(?:im_end|eot_id|endoftext|end|eom_id)\|>|<end_of_turn>|</s>))+\s*$")


def without_end_marker(sentence: str) -> str:
    """`sentence` without the chat template's end-of-turn markers at its end."""
    return _END_MARKERS.sub("", sentence)


def tool_syntax_in(sentence: str) -> str | None:
    """The first piece of tool-call syntax in `sentence`, or None when there is none."""
    found = _TOOL_SYNTAX.search(sentence)
    return found.group(0) if found is not None else None


def speakable(sentence: str, model_only: ModelOnlyText | None = None) -> str | None:
    """`sentence` (without an end-of-turn marker at its end), or None when it carries tool-call
    syntax or words meant for the model only (`unspeakable_in`), or nothing else, and must not
    be spoken or shown."""
    sentence = without_end_marker(sentence)
    unspeakable = unspeakable_in(sentence, model_only or MODEL_ONLY)
    return None if unspeakable is not None or not sentence.strip() else sentence


# --- text meant for the model only -------------------------------------------------------------

COPIED_RUN_WORDS = 6  # this many words in a row from the model's instructions: reading them out
_SHORTEST_COPY = 3  # a sentence shorter than the run is a copy when all of it (3 words or more) is
_ADDRESSEE = ("the", "user")  # how instructions name the person; speaking to them, the robot says "you"
_WORD = re.compile(r"[a-z0-9]+")
# what a tool error's hint tells the model to say: up to its next instruction
_TOLD = re.compile(r"\s*tell the user (?:that )?(.+?)(?=[,;]| and |$)", re.IGNORECASE)


def _words(text: str) -> list[str]:
    return _WORD.findall(text.lower())


class ModelOnlyText:
    """Text the model reads that is not for the person's ears: the system prompt, the gate's hints
    (`gate.model_only_texts`), the loop's step hints (`prompt.STEP_HINTS`), a tool error's hint. A
    small model sometimes reads such text out ("Please tell the user which one they mean"); a
    sentence that reproduces it is never spoken.

    Two signs, neither a list of phrases: `COPIED_RUN_WORDS` words in a row of such a text (or
    all of a shorter sentence, from 3 words), and the person named as the instructions name
    them ("the user"). A reply that only follows a hint shares a few words with it ("I do not
    know that place" after "tell the user you do not know that place") and stays speakable.
    """

    def __init__(self, texts: Iterable[str] = ()) -> None:
        self._runs: set[tuple[str, ...]] = set()
        for text in texts:
            self.add(text)

    def copy(self) -> ModelOnlyText:
        """A copy to add one turn's texts to (its tool errors' hints)."""
        other = ModelOnlyText()
        other._runs = set(self._runs)
        return other

    def add(self, text: str, *, short_copies: bool = True) -> None:
        """Remember `text` as model-only (every run of 3 to `COPIED_RUN_WORDS` of its words; only the
        long runs without `short_copies`: a tool's description shares short runs with true answers,
        "it is charging")."""
        words = _words(text)
        for size in range(_SHORTEST_COPY if short_copies else COPIED_RUN_WORDS, COPIED_RUN_WORDS + 1):
            self._runs.update(tuple(words[i : i + size]) for i in range(len(words) - size + 1))

    def add_said(self, text: str) -> None:
        """Remember what the robot has said this turn (a tool's phrase): the model saying one of
        its sentences again ("I am at the bathroom now.", a small model's echo) is not said twice."""
        self.add(text, short_copies=False)
        sentences = (tuple(_words(s)) for s in re.split(r"(?<=[.!?])\s+", text))
        self._runs.update(words for words in sentences if len(words) >= _SHORTEST_COPY)  # a short one whole

    def add_hint(self, hint: str) -> None:
        """Remember a tool error's hint as model-only, all but what it tells the model to say
        ("tell the user the robot cannot get to the balcony"): that, said, is the answer, not the
        hint read out. The instructions around it ("…, name the known places and ask which one
        they mean") stay model-only."""
        told = _TOLD.match(hint)
        for part in (hint,) if told is None else (hint[: told.start(1)], hint[told.end(1) :]):
            self.add(part)

    def copied_in(self, sentence: str) -> str | None:
        """The model-only words `sentence` reproduces, or None when it reproduces none."""
        words = _words(sentence)
        size = COPIED_RUN_WORDS if len(words) > COPIED_RUN_WORDS else len(words)
        if size >= _SHORTEST_COPY:
            for i in range(len(words) - size + 1):
                if tuple(words[i : i + size]) in self._runs:
                    return " ".join(words[i : i + size])
        return " ".join(_ADDRESSEE) if _ADDRESSEE in itertools.pairwise(words) else None


MODEL_ONLY = ModelOnlyText([SYSTEM_PROMPT, *model_only_texts(), *(hint.format('') for hint in STEP_HINTS)])


def unspeakable_in(sentence: str, model_only: ModelOnlyText = MODEL_ONLY) -> str | None:
    """The first piece of `sentence` that must never be spoken or shown: tool-call syntax, or
    words meant for the model only (`ModelOnlyText`); None when there is none."""
    return tool_syntax_in(sentence) or model_only.copied_in(sentence)


# --- a claim that something was done ------------------------------------------------------------

# After the check before acting refused a call and nothing else acted, a small model still often
# words the refused action as done ("The projector is now on."): a false claim the person would
# believe. Such a sentence says a state is now on/off, that the robot is on its way, that it is
# (or has been) doing an action, or "done" — and denies nothing.
_CLAIM = re.compile(
    r"\b(?:is|are|'s) now (?:on|off|running|playing|started|moving|driving|connected|charging)\b"
    r"|\b(?:is|are|'s|has been|have been) (?:now )?(?:turned|switched|started|ended|stopped) (?:on|off|now)?"
    r"|\b(?:has|have) (?:now |just )?(?:started|ended|begun|connected)\b"
    r"|\b(?:am|'m|is|are|'s) (?:now (?:at|in) the|in a (?:video )?call)\b"
    r"|\b(?:i am|i'm) (?:at|in) the (?:\w+ ){1,3}now\b"  # "I am in the living room now." (a refused drive)
    r"|\bon (?:my|its|our) way\b"
    r"|^(?:(?:ok|okay|sure|alright|all right|right)\W+)?done\b"
    r"|\b(?:i|i'?ve|i have|i'?m|i am|we'?re|it'?s|it is)\s+(?:now\s+|just\s+|already\s+)?"
    r"(?:turned|switched|started|starting|called|calling|ended|ending|driving|driven|drove|heading|headed|gone"
    r"|moving|moved|navigating|navigated|turning|switching|returning|returned|connecting|connected|dialling"
    r"|dialing|ringing|rang|going to the|docking|docked)\b"
    r"|^(?:(?:ok|okay|sure|alright|all right|right)\W+)?(?:calling|ringing|dialling|dialing|heading|driving"
    r"|navigating|moving|going|turning|switching|starting|returning|docking)\b",
    re.IGNORECASE,
)
# "n't", or its apostrophe dropped ("dont", "havent"), but not every word ending in "nt" ("front")
_DENIAL = re.compile(r"\b(?:not|never|no|won'?t|cannot|can'?t)\b|n't\b|\b(?:do|does|did|is|are|was|were|has|have"
                     r"|had|could|would|should|must|need)nt\b", re.IGNORECASE)


def claimed_action_in(sentence: str) -> str | None:
    """The words of `sentence` that claim an action was done or is under way ("The projector is
    now on.", "On my way.", "Calling Anna now."), or None: a sentence that denies anything
    ("I won't", "I haven't turned it on") claims nothing."""
    text = sentence.strip().replace("\u2019", "'")
    if _DENIAL.search(text):
        return None
    found = _CLAIM.search(text)
    return found.group(0).strip() if found is not None else None


# What the robot is, was or is not doing, said as a fact ("The projector is not turned on.", "I am
# already at my charging dock."): after a turn whose every call was refused, the model was told
# nothing of the robot's state, and such a sentence is a guess.
_STATE = re.compile(
    r"\b(?:is|are|am|'m|'s|was|were)(?:n't)?\s+(?:not\s+|no longer\s+)?(?:already\s+|still\s+|currently\s+|now\s+)?"
    r"(?:at|in|on|off|moving|driving|charging|docked|connected|turned|switched|running|playing|stopped|parked)\b",
    re.IGNORECASE,
)


def state_claimed_in(sentence: str) -> str | None:
    """The words of `sentence` that state what the robot or a device is doing, or None."""
    found = _STATE.search(sentence.replace("\u2019", "'"))
    return found.group(0) if found is not None else None


# A small model speaks of itself as its instructions name it, "the robot"; the robot says "I".
_SELF = re.compile(r"\bthe robot(?:'s\b|\s+(is|isn't|has|hasn't|was|wasn't|does|doesn't|did|didn't|can|can't|cannot"
                   r"|could|couldn't|will|won't|would|should|must|may|might|needs|wants"
                   # a verb of its own (not "the robot arms are"): "The robot sees a small image of the room."
                   r"|sees|hears|knows|goes|says|thinks|finds|gets|makes|moves|drives|works|stays|waits|keeps|shows"
                   r"|comes|remains|uses|takes|seems|looks|sounds|feels|sits|stands|tries|carries|heads|stops"
                   # and what it did: "The robot took a picture and captured an image." (audio test v27)
                   r"|took|went|drove|came|moved|arrived|reached|returned|called|rang|ended|turned|switched|started"
                   r"|stopped|made|got|saw|found|captured|checked|looked|tried|left|heard|said)\b)",
                   re.IGNORECASE)
# the robot as the object of the person's doing: "Please tell the robot which place you mean."
_SELF_OBJECT = re.compile(r"\b(tell|ask|show|give|let|help|follow|call|wake|remind)\s+the robot\b", re.IGNORECASE)
# … and sometimes in the second person, as the person would say it to the robot: "Your battery is at
# 83.8%.", "You are currently at the charging dock, facing north." (texts v27 and v28). Only the
# robot's own things and its place or motion: "you are in the kitchen" may be where the person is.
_YOUR_OWN = re.compile(r"\b(your) (battery|charge|charging dock|dock|camera|projector|position|location|heading)\b",
                       re.IGNORECASE)
_YOU_ARE_THERE = re.compile(r"\b(you are|you're)((?: currently| now| still| already| right now)? "
                            r"(?:at|near|facing|charging|moving|not moving|driving|on my way|on your way)\b)",
                            re.IGNORECASE)
_FIRST_PERSON = {"is": "am", "isn't": "am not", "has": "have", "hasn't": "haven't", "does": "do", "doesn't": "don't",
                 "goes": "go", "tries": "try", "carries": "carry"}


def in_first_person(sentence: str) -> str:
    """`sentence` with the robot's self in the first person: "The robot's battery is at 94%." ->
    "My battery is at 94%.", "The robot is already at its dock." -> "I am already at my dock.", "Please tell
    the robot which one." -> "Please tell me which one."."""
    def first(match: re.Match[str]) -> str:
        verb = match.group(1)
        if verb is None:
            return "my"
        verb = verb.lower()
        plain_verb = verb[:-1] if verb.endswith("s") and verb != "was" else verb  # "needs" → "need"
        return "I " + _FIRST_PERSON.get(verb, plain_verb)

    plain = sentence.replace("\u2019", "'")
    out = _SELF_OBJECT.sub(r"\1 me", _SELF.sub(first, plain))
    out = _YOUR_OWN.sub(lambda m: ("My" if m.group(1)[0] == "Y" else "my") + " " + m.group(2), out)
    out = _YOU_ARE_THERE.sub(lambda m: "I am" + m.group(2).replace("on your way", "on my way"), out)
    if out == plain:
        return sentence
    out = re.sub(r"\bits\b", "my", out)  # "at its charging dock": the robot's own
    return out[:1].upper() + out[1:]


@dataclass(frozen=True, slots=True)
class TurnActions:
    """What the turn's tool calls did so far, to tell a false claim from a true one. Before any
    tool ran, a claim may announce the call that follows it. After tools ran, a claim is false
    when no action succeeded ("The robot is now at the front door." after a camera look-up),
    or when it names only actions that did not, or that were never called ("The video call with
    Ben has started." after the call was refused and only the projector went on; "The projector
    is now on." after only a drive: text v19's compound-2). `actuators`: the robot's tools that
    act (not `read_only`)."""

    calls: Sequence[ToolCalled] = ()
    outcomes: Sequence[ToolReturned] = ()
    read_only: Collection[str] = ()
    actuators: Collection[str] = ()

    def false_claim(self, sentence: str) -> str | None:
        """The words of `sentence` that claim an action this turn did not do, or that state what
        the robot is doing after the check before acting refused every call of the turn; or None."""
        if self.calls and all(r.error == NOT_REQUESTED for r in self.outcomes):
            state = state_claimed_in(sentence)
            if state is not None:
                return state
        claim = claimed_action_in(sentence) if self.calls else None
        if claim is None:
            return None
        actions = [(c, r) for c, r in zip(self.calls, self.outcomes, strict=True) if c.name not in self.read_only]
        ran = [c for c, r in actions if r.error is None]
        if not ran:
            return claim
        unrun = [(c.name, c.arguments) for c, r in actions if r.error is not None]
        ran_names = {c.name for c in ran}
        unrun += [(tool, {}) for tool in self.actuators if tool not in ran_names]
        if any(names(sentence, tool, arguments) for tool, arguments in unrun) and not any(
                names(sentence, c.name, c.arguments) for c in ran):
            return claim
        return None



# --- a figure nobody gave the model --------------------------------------------------------------

# A small model answers "how much battery?" from its head ("The battery is at 80%") when it skips
# the look-up, or works out distances and times it was never told. A measured figure (a percentage,
# a distance, a time, an angle) in a sentence must come from the conversation the model was given
# (the tool results, the person's words); one that does not is invented, and the sentence is not said.
_NUMBER = re.compile(r"\d+(?:\.\d+)?")
_FIGURE = re.compile(
    r"(\d+(?:\.\d+)?)\s*(?:%|percent\b|per cent\b|met(?:er|re)s?\b|m\b|cm\b|seconds?\b|secs?\b|minutes?\b"
    r"|mins?\b|hours?\b|degrees?\b|km/h\b|m/s\b|volts?\b)",
    re.IGNORECASE,
)
_SAME = 0.5  # rounding: "83%" for 83.33, "84 percent" for 83.5


def figures_in(texts: Iterable[str]) -> frozenset[float]:
    """Every number in `texts` (the conversation the model was given)."""
    return frozenset(float(n) for text in texts for n in _NUMBER.findall(text))


def invented_figure_in(sentence: str, known: Collection[float]) -> str | None:
    """The first measured figure in `sentence` that no number in `known` gives (as it is, as a
    percentage of a fraction, or in degrees of an angle in radians), or None."""
    for found in _FIGURE.finditer(sentence):
        value = float(found.group(1))
        if not any(abs(value - k) <= _SAME or abs(value - 100 * k) <= _SAME or abs(value - math.degrees(k)) <= _SAME
                   for k in known):
            return found.group(0)
    return None
