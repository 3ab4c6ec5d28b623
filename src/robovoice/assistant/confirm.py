"""Spoken confirmation before a call that cannot be taken back, when the words may be misheard.

A tool whose manifest declares a ``confirm`` phrase ("Shall I call {contact}?") is not run
on a transcript the speech-to-text model was in doubt of (`voice.confidence.doubtful`): the
call is held, the robot asks the question, and the next thing the person says answers it
locally, without a model step — a yes runs the held call, a no drops it. Anything else, or
nothing within `WINDOW_S`, drops it as well (a question nobody answered is a no), and the
words go to the model as a new request. Typed text is never in doubt: nothing is asked then.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from robovoice.llm.base import ToolCallRequested
from robovoice.manifest.voice import VoiceDecl, fill

WINDOW_S = 30.0  # how long a question waits for its answer (the robot's own clock)

DECLINED = "All right, I won't."

_FILLER = r"(?:hey jarvis|jarvis|oh|well|um+|uh+|er+|then|robot|dear|love|thanks|thank you|please)"
_YES = re.compile(
    r"^(?:" + _FILLER + r"\W+)*(?:yes|yeah|yep|yup|aye|sure|okay|ok|right|correct|of course|certainly|"
    r"go ahead|go on|do it|do that|please do|yes please|that's right|that is right|that's it|"
    r"absolutely|definitely|indeed|i do|i did|you may|you can)(?:\W+(?:" + _FILLER +
    r"|yes|do it|go ahead|call (?:him|her|them)|that's right))*\W*$", re.IGNORECASE)
_NO = re.compile(
    r"^(?:" + _FILLER + r"\W+)*(?:no|nope|nah|no thanks|no thank you|don't|do not|not now|not yet|"
    r"never mind|forget it|leave it|cancel(?: that| it)?|wrong|that's wrong|i didn't|i did not)"
    r"(?:\W+(?:" + _FILLER + r"|no|don't|not now|leave it|forget it|never mind))*\W*$", re.IGNORECASE)


def reply_to_question(text: str) -> bool | None:
    """True for a yes ("Yes, please."), False for a no ("No, don't."), None for anything else
    ("No, call Ben." is a new request, not an answer)."""
    text = text.strip()
    if _YES.match(text):
        return True
    if _NO.match(text):
        return False
    return None


def confirm_question(voice: Mapping[str, VoiceDecl], name: str, arguments: Mapping[str, Any]) -> str | None:
    """The tool's confirm question filled from the call's arguments; None when it declares
    none (or it does not fill: the call then runs unasked, as every call did before)."""
    decl = voice.get(name)
    return fill(decl.say.confirm, arguments) if decl is not None else None


@dataclass(frozen=True, slots=True)
class Held:
    """A call waiting for the person's yes."""

    request: ToolCallRequested
    question: str
    asked_at: float


class Confirmations:
    """The one call a conversation holds for confirmation (a newer question replaces it)."""

    def __init__(self, clock: Callable[[], float] = time.monotonic, window_s: float = WINDOW_S) -> None:
        self._clock = clock
        self.window_s = window_s
        self._held: Held | None = None

    def hold(self, request: ToolCallRequested, asked: str) -> None:
        self._held = Held(request, asked, self._clock())

    @property
    def held(self) -> Held | None:
        return self._held

    def take(self, text: str) -> tuple[Held, bool] | None:
        """The held call and the person's answer to it, when `text` answers it in time; the call
        is no longer held either way (a new request or silence drops it)."""
        held, self._held = self._held, None
        if held is None or self._clock() - held.asked_at > self.window_s:
            return None
        answer = reply_to_question(text)
        return None if answer is None else (held, answer)

    def clear(self) -> None:
        self._held = None
