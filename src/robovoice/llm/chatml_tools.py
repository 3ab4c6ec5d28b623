"""The prompt protocol of the embedded model: ChatML with llama-cpp-python's
``chatml-function-calling`` tool format, rendered here as plain text.

The model answers either ``message:\\n<text>`` or one or more
``functions.<name>:\\n<JSON arguments>``; a grammar makes it pick one of those
heads, and a JSON-schema grammar keeps each argument object valid. This is the
format the notes measured as the best tool caller for Qwen2.5-Coder-1.5B.

We render it ourselves instead of calling ``create_chat_completion`` because
the handler in llama-cpp-python 0.3.36 (a) raises "Automatic streaming tool
choice is not supported" when a streamed turn turns into a tool call, (b)
constrains a plain reply with the follow-up grammar, so it is always empty,
(c) drops ``tool`` messages (results never reach the model), (d) leaves the
tools' descriptions out of the prompt, and (e) keeps the ':' in the name of a
second call, so a turn never holds more than one call. Everything here is plain
text in, text out, and tested without a model.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

from robovoice.errors import LLMError
from robovoice.llm.base import ChatMessage, ToolSpec

IM_START = "<|im_start|>"
IM_END = "<|im_end|>"
MESSAGE_HEAD = "message:"
FUNCTION_PREFIX = "functions."

_FORMAT = (
    "\n\nYou can respond to users messages with either a single message or one or more function calls."
    "\n\nTo respond with a message begin the message with 'message:', use the following format:"
    "\n\nmessage:"
    "\n<message>"
    "\n\nTo respond with one or more function calls begin the message with 'functions.<function_name>:', "
    "use the following format:"
    "\n\nfunctions.<function_name>:"
    '\n{ "arg1": "value1", "arg2": "value2" }'
    "\nfunctions.<function_name>:"
    '\n{ "arg1": "value1", "arg2": "value2" }'
)


def tools_section(tools: Sequence[ToolSpec]) -> str:
    """The block appended to the system message that lists the functions."""
    if not tools:
        return ""
    lines = ["\n\nYou have access to the following functions:\n"]
    for tool in tools:
        lines.append(f"\n// {tool.description}" if tool.description else "")
        lines.append(f"\n{FUNCTION_PREFIX}{tool.name}:\n{json.dumps(dict(tool.parameters), sort_keys=True)}\n")
    return "".join(lines) + _FORMAT


def _block(role: str, text: str) -> str:
    return f"{IM_START}{role}\n{text}{IM_END}\n"


def render_calls(calls: Sequence[tuple[str, str]]) -> str:
    """Tool calls (name, JSON arguments) the way the model writes them."""
    return "\n".join(f"{FUNCTION_PREFIX}{name}:\n{arguments}" for name, arguments in calls)


def render_system(system_text: str, tools: Sequence[ToolSpec]) -> str:
    """The system block: the unchanging prefix of every turn (what `warm_up` evaluates)."""
    return _block("system", system_text + tools_section(tools))


def listed_tools(messages: Sequence[ChatMessage], offered: Sequence[ToolSpec],
                 kept: tuple[str, Sequence[ToolSpec]] | None) -> Sequence[ToolSpec]:
    """The tools a turn's prompt lists. `kept` is the system text and tools `warm_up` evaluated:
    when the turn has that system text and offers some of those tools (or none), the prompt lists
    them all, so a step offering fewer keeps the evaluated prefix and only the grammar narrows
    the choice. Listing the offered ones alone changed the system block: on 2 cores the whole
    prompt (~1,250 tokens, ~35 s on the slower VM) was evaluated again for that step and the next."""
    if kept is None or not messages or messages[0].role != "system" or messages[0].text != kept[0]:
        return offered
    return kept[1] if all(tool in kept[1] for tool in offered) else offered


def render_prompt(messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]) -> str:
    """The whole prompt, ending with the open assistant turn."""
    if any(m.has_audio for m in messages):
        raise LLMError("the embedded model takes text only; transcribe the audio first")
    out: list[str] = []
    rest = list(messages)
    system_text = rest.pop(0).text if rest and rest[0].role == "system" else ""
    if system_text or tools:
        out.append(render_system(system_text, tools))
    names_by_id: dict[str, str] = {}
    for message in rest:
        if message.role == "system":
            out.append(_block("system", message.text))
        elif message.role == "user":
            out.append(_block("user", message.text))
        elif message.role == "assistant":
            parts: list[str] = []
            if message.text:
                parts.append(f"{MESSAGE_HEAD}\n{message.text}" if tools else message.text)
            if message.tool_calls:
                names_by_id.update((c.id, c.name) for c in message.tool_calls)
                parts.append(render_calls([(c.name, c.arguments) for c in message.tool_calls]))
            out.append(_block("assistant", "\n".join(parts)))
        else:  # a tool result, shown to the model the way Qwen2.5 was trained to read them
            name = message.name or names_by_id.get(message.tool_call_id or "", "")
            head = f"{FUNCTION_PREFIX}{name} returned:\n" if name else ""
            out.append(_block("user", f"<tool_response>\n{head}{message.text}\n</tool_response>"))
    out.append(f"{IM_START}assistant\n")
    return "".join(out)


def _literal(text: str) -> str:
    return json.dumps(text)  # a GBNF string literal: double quotes, backslash escapes


def head_grammar(tools: Sequence[ToolSpec]) -> str:
    """GBNF for the first line of an answer: a message, or a call of one of ``tools``."""
    names = " | ".join(_literal(f"{FUNCTION_PREFIX}{t.name}:") for t in tools)
    return f"root ::= functions | {_literal(MESSAGE_HEAD)}\nfunctions ::= {names}\n"


def next_call_grammar(tools: Sequence[ToolSpec]) -> str:
    """GBNF after a call: another call, or nothing (the model's end-of-turn token is then the
    only choice; a literal ``"<|im_end|>"`` would have to be spelled out as text)."""
    names = " | ".join(_literal(f"{FUNCTION_PREFIX}{t.name}:") for t in tools)
    return f"root ::= functions?\nfunctions ::= {names}\n"


@dataclass(frozen=True, slots=True)
class Head:
    """What the model chose to do next."""

    kind: Literal["message", "call", "end"]
    tool: ToolSpec | None = None  # for "call"


def parse_head(text: str, tools: Sequence[ToolSpec]) -> Head:
    """``message:`` → message, ``functions.x:`` → call of x; nothing (or anything else) → end."""
    text = text.strip()
    if text.startswith(MESSAGE_HEAD.rstrip(":")):
        return Head("message")
    if text.startswith(FUNCTION_PREFIX):
        name = text[len(FUNCTION_PREFIX) :].rstrip(":").strip()
        for tool in tools:
            if tool.name == name:
                return Head("call", tool)
    return Head("end")
