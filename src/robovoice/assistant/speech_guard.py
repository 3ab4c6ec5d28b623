"""The last check before words reach the user: never speak or print raw tool-call syntax.

Backends turn calls written as text into real calls (`robovoice.llm.text_calls`), but a model
or server can still leak its syntax (a broken call, a format not recognised, control tokens).
Speaking "functions dot get battery state colon" to an older adult is worse than silence, so a
sentence that carries such syntax is dropped whole. Pure functions: the callers (speech output,
the chat printer) log what they drop.
"""

from __future__ import annotations

import re

_TOOL_SYNTAX = re.compile(
    r"</?tool_call>|</?tool_response>|</?function_call>|<function=|</function>"
    r"|\[/?TOOL_CALLS\]|\[/?TOOL_RESULTS\]|\[/?AVAILABLE_TOOLS\]"
    r"|<\|[A-Za-z_][\w-]*\|>"  # chat-template control tokens: <|im_start|>, <|python_tag|>, <|eot_id|>
    r"|<(?:start|end)_of_turn>"
    r"|</?think>"  # a reasoning model's thinking, passed through by a server without a reasoning parser
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


def speakable(sentence: str) -> str | None:
    """`sentence` (without an end-of-turn marker at its end), or None when it carries tool-call
    syntax, or nothing else, and must not be spoken or shown."""
    sentence = without_end_marker(sentence)
    return None if tool_syntax_in(sentence) is not None or not sentence.strip() else sentence
