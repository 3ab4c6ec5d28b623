"""The check before acting: an actuation tool runs only when the user asked for it now.

Read-only tools (MCP ``readOnlyHint``) always run: looking things up is never an unwanted
action. An actuation tool the model calls is refused locally — it never reaches the robot —
when the user's words (`intent.read_request`) asked for no action at all (a negated or
postponed request, an ability question, talk that merely mentions a place or a person), or
when its arguments name only what the user said *not* to do ("don't call Anna, call Ben":
a call to Anna). The model gets a structured ``not_requested`` tool error whose hint tells
it how to answer instead, so the turn still ends with words the person understands.

Audio given to an audio-capable model has no words to read: nothing is refused then.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from typing import Any

from robovoice.assistant.intent import ClauseKind, Intent, words
from robovoice.llm.base import ToolSpec

log = logging.getLogger(__name__)

NOT_REQUESTED = "not_requested"

_HINTS = {
    ClauseKind.NEGATED: "The user asked you not to do this now. Do not do it. Acknowledge in one short sentence.",
    ClauseKind.ABILITY: "The user only asked whether you can do this, not to do it now. Say in one short "
                        "sentence that you can, if they ask you to.",
    ClauseKind.STATEMENT: "The user did not ask you to do anything; they were telling you something. Reply "
                          "kindly in one short sentence without using tools.",
    ClauseKind.QUESTION: "The user asked a question, not for an action. Answer it in one short sentence.",
}


def refusal(intent: Intent | None, spec: ToolSpec | None, arguments: Mapping[str, Any]) -> dict[str, Any] | None:
    """The ``{error, message, hint, details}`` body that refuses this call, or None to let it run."""
    if intent is None or (spec is not None and spec.read_only):
        return None
    name = spec.name if spec is not None else "?"
    why = intent.refusal
    if why is None:
        negated = intent.negated_words()
        named = [w for value in arguments.values() if isinstance(value, str) for w in words(value)]
        if not named or not set(named) <= negated:
            return None
        why = ClauseKind.NEGATED
    log.info("refused %s%s: the user did not ask for it (%s)", name, dict(arguments), why.value)
    return {
        "error": NOT_REQUESTED,
        "message": f"not done: the user did not ask for {name} now ({why.value})",
        "hint": _HINTS[why],
        "details": {"tool": name, "reason": why.value},
    }
