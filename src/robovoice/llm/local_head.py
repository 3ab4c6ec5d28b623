"""The embedded model's first decision in a turn with tools: answer (``message:``) or call a tool
(``functions.<name>:``), read off the logits of the head's first token and optionally tilted.

``tool_bias`` is added to the logits of the call head's first token (``functions`` and its
prefixes) at that one position, so the model asks the robot when it was nearly as inclined to as
to answer from memory. After a tool result (the model has the data) the decision is left alone.
The margin is measured before the bias; docs/llm.md has the measurement behind the default.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from robovoice.llm import chatml_tools as fmt
from robovoice.llm.base import ChatMessage, ToolSpec

# The default `LocalLlamaBackend.tool_bias` in logit units. Measured on the text evaluation with the
# assistant's prompt (docs/llm.md): questions about the robot's state sat at margins down to -0.57,
# small talk at -2.09 and below; 1.3 is near the middle of that gap.
TOOL_BIAS = 1.3


@dataclass(frozen=True, slots=True)
class HeadDecision:
    """What the model chose at the head of its answer, and by how much: the logit of the best
    call-head token minus that of the best message-head token, before ``tool_bias``."""

    head: fmt.Head
    margin: float


class HeadTilt:
    """A llama.cpp logits processor for the first token of the head: records the margin between
    the call head and the message head, and adds ``bias`` to the call head's tokens. Later tokens
    (the tool's name) are left alone, so the bias never favours one tool over another."""

    def __init__(self, call_ids: list[int], message_ids: list[int], bias: float) -> None:
        self.call_ids = call_ids
        self.message_ids = message_ids
        self.bias = bias
        self.margin: float | None = None

    def __call__(self, _input_ids: Any, scores: Any) -> Any:
        if self.margin is not None:  # past the first token
            return scores
        self.margin = float(scores[self.call_ids].max() - scores[self.message_ids].max())
        if self.bias:
            scores = scores.copy()
            scores[self.call_ids] += self.bias
        return scores


def head_token_ids(llama: Any, tools: Sequence[ToolSpec]) -> tuple[list[int], list[int]]:
    """Token ids (of the `llama_cpp.Llama` model's vocabulary) that can start a call head and the
    message head: every prefix of a head that is a single token ("f", "func", "functions", …; "m",
    "mess", "message"), which is what the head grammar lets through as the first token."""

    def starts(heads: list[str]) -> list[int]:
        ids: set[int] = set()
        for head in heads:
            for end in range(1, len(head) + 1):
                piece = head[:end].encode("utf-8")
                tokens = llama.tokenize(piece, add_bos=False, special=False)
                if len(tokens) == 1 and llama.detokenize(tokens) == piece:
                    ids.add(tokens[0])
        return sorted(ids)

    return starts([f"{fmt.FUNCTION_PREFIX}{t.name}:" for t in tools]), starts([fmt.MESSAGE_HEAD])


def bias_for(messages: Sequence[ChatMessage], tool_bias: float) -> float:
    """`tool_bias` for a step that answers the user's words; none after tool results. There,
    measured, single requests that should now be answered reach margins of -1.4 while the
    second calls of multi-step requests sit at -1.6 to -1.9: no bias would separate them."""
    return tool_bias if messages and messages[-1].role == "user" else 0.0
