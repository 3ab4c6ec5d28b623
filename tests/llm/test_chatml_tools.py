"""The embedded model's prompt protocol, as plain text (no model needed)."""

from __future__ import annotations

import pytest

from robovoice.errors import LLMError
from robovoice.llm.base import AudioPart, ChatMessage, ToolCall, ToolSpec
from robovoice.llm.chatml_tools import (
    Head,
    head_grammar,
    listed_tools,
    next_call_grammar,
    parse_head,
    render_prompt,
    render_system,
)

SYSTEM = ChatMessage("system", "You are the voice assistant of a home robot.")


def test_prompt_lists_tools_with_descriptions_and_ends_open(tools: list[ToolSpec]) -> None:
    prompt = render_prompt([SYSTEM, ChatMessage("user", "Go to the kitchen")], tools)
    assert prompt.startswith("<|im_start|>system\nYou are the voice assistant of a home robot.")
    assert "// Drive the robot to a known place in the home.\nfunctions.navigate_to:\n{" in prompt
    assert '"required": ["target"]' in prompt
    assert "functions.stop_robot:" in prompt and "functions.set_projector_power:" in prompt
    assert "<|im_start|>user\nGo to the kitchen<|im_end|>\n" in prompt
    assert prompt.endswith("<|im_start|>assistant\n")


def test_the_system_block_is_a_prefix_of_every_turn(tools: list[ToolSpec]) -> None:
    """What warm_up evaluates must be exactly where every turn's prompt starts."""
    prefix = render_system(SYSTEM.text, tools)
    for user in ["Hello", "Stop!", "Switch the projector on"]:
        assert render_prompt([SYSTEM, ChatMessage("user", user)], tools).startswith(prefix)


def test_tool_calls_and_results_are_rendered(tools: list[ToolSpec]) -> None:
    history = [
        SYSTEM,
        ChatMessage("user", "Stop and switch the projector off"),
        ChatMessage(
            "assistant",
            "",
            tool_calls=(ToolCall("a", "stop_robot", "{}"), ToolCall("b", "set_projector_power", '{"on": false}')),
        ),
        ChatMessage("tool", '{"stopped": true}', tool_call_id="a"),
        ChatMessage("tool", '{"on": false}', tool_call_id="b"),
        ChatMessage("assistant", "Done."),
    ]
    prompt = render_prompt(history, tools)
    assert (
        "<|im_start|>assistant\nfunctions.stop_robot:\n{}\nfunctions.set_projector_power:\n"
        '{"on": false}<|im_end|>\n' in prompt
    )
    assert '<tool_response>\nfunctions.stop_robot returned:\n{"stopped": true}\n</tool_response>' in prompt
    assert "functions.set_projector_power returned:" in prompt
    assert "<|im_start|>assistant\nmessage:\nDone.<|im_end|>" in prompt


def test_a_step_offering_fewer_tools_lists_all_that_warm_up_evaluated(tools: list[ToolSpec]) -> None:
    system = ChatMessage("system", "Be brief.")
    messages = [system, ChatMessage("user", "Go to the kitchen")]
    kept = ("Be brief.", tools)
    assert listed_tools(messages, tools[1:], kept) == tools  # the prefix stays; the grammar narrows
    assert listed_tools(messages, [], kept) == tools
    assert render_prompt(messages, listed_tools(messages, tools[:1], kept)) == render_prompt(messages, tools)
    other = ToolSpec("open_door", "Open the door")
    assert listed_tools(messages, [other], kept) == [other]  # not among them: the offered ones
    assert listed_tools([ChatMessage("system", "Other."), messages[1]], tools[1:], kept) == tools[1:]
    assert listed_tools(messages, tools[1:], None) == tools[1:]


def test_without_tools_it_is_plain_chatml() -> None:
    prompt = render_prompt([ChatMessage("user", "Hi"), ChatMessage("assistant", "Hello!")], [])
    assert prompt == "<|im_start|>user\nHi<|im_end|>\n<|im_start|>assistant\nHello!<|im_end|>\n<|im_start|>assistant\n"


def test_audio_is_refused() -> None:
    with pytest.raises(LLMError, match="text only"):
        render_prompt([ChatMessage("user", (AudioPart(b"RIFF"),))], [])


def test_grammars_name_every_tool(tools: list[ToolSpec]) -> None:
    head = head_grammar(tools)
    assert head.startswith('root ::= functions | "message:"')
    assert '"functions.navigate_to:" | "functions.stop_robot:" | "functions.set_projector_power:"' in head
    assert next_call_grammar(tools).startswith("root ::= functions?\n")


def test_heads_are_parsed(tools: list[ToolSpec]) -> None:
    assert parse_head("message", tools) == Head("message")
    assert parse_head("message:", tools) == Head("message")
    assert parse_head("functions.stop_robot:", tools) == Head("call", tools[1])
    assert parse_head("functions.stop_robot", tools) == Head("call", tools[1])
    assert parse_head("", tools) == Head("end")
    assert parse_head("functions.fly_away:", tools) == Head("end")
