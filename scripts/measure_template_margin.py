"""The first token of an answer under the GGUF's own chat template (llama-cpp-python's server
without ``--chat_format``): is it a call or words? docs/llm.md, "the GGUF's own chat template".

Renders the exact request `OpenAICompatBackend` sends for the assistant's first step (its
system prompt, the sim robot's tools, ``tool_choice: "auto"``, the question) with the GGUF's
``tokenizer.chat_template``, as that server does, evaluates it and prints the five best first
tokens with their logits, then the greedy answer. ``--describe NAME=TEXT`` replaces a tool's
description (to see how much of the decision the description's wording carries).

    nice -n 19 .venv/bin/python scripts/measure_template_margin.py "how much battery do you have?"
"""

from __future__ import annotations

import argparse
import asyncio
from typing import Any

import numpy as np
from llama_cpp import Llama
from llama_cpp.llama_chat_format import Jinja2ChatFormatter

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.prompt import SYSTEM_PROMPT
from robovoice.config import RobotConfig
from robovoice.llm.base import ChatMessage, ToolSpec
from robovoice.llm.model_store import ensure_default_model
from robovoice.llm.openai_compat import OpenAICompatBackend


async def _request(question: str) -> dict[str, Any]:
    async with connect_robot(RobotConfig(address="sim://")) as link:
        tools: list[ToolSpec] = list(await link.tools.specs())
    backend = OpenAICompatBackend("http://127.0.0.1:1/v1", "qwen")  # only builds the body
    try:
        return backend.request_body([ChatMessage("system", SYSTEM_PROMPT), ChatMessage("user", question)], tools)
    finally:
        await backend.aclose()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("question")
    parser.add_argument("--describe", action="append", default=[], metavar="NAME=TEXT")
    parser.add_argument("--max-tokens", type=int, default=40)
    args = parser.parse_args()
    body = asyncio.run(_request(args.question))
    for item in args.describe:
        name, _, text = item.partition("=")
        found = [t for t in body["tools"] if t["function"]["name"] == name]
        if not found or not text:
            parser.error(f"--describe {item!r}: give NAME=TEXT with NAME one of the offered tools")
        found[0]["function"]["description"] = text
    llm = Llama(str(ensure_default_model()), n_ctx=4096, n_threads=2, verbose=False)
    formatter = Jinja2ChatFormatter(llm.metadata["tokenizer.chat_template"], eos_token="<|im_end|>", bos_token="")
    prompt = formatter(messages=body["messages"], tools=body["tools"], tool_choice=body["tool_choice"]).prompt
    tokens = llm.tokenize(prompt.encode(), add_bos=False, special=True)
    llm.eval(tokens)
    logits = np.ctypeslib.as_array(llm._ctx.get_logits(), shape=(llm.n_vocab(),)).copy()  # type: ignore[no-untyped-call]
    best = np.argsort(-logits)[:5]
    tool_call = llm.tokenize(b"<tool_call>", add_bos=False, special=True)[0]
    print(f"prompt: {len(tokens)} tokens; <tool_call> token: {float(logits[tool_call]):.2f}")
    for token in best:
        print(f"  {llm.detokenize([int(token)], special=True).decode(errors='replace')!r:>12} "
              f"{float(logits[token]):.2f}")
    answer = llm.create_completion(tokens, max_tokens=args.max_tokens, temperature=0.0)
    print("greedy answer:", repr(answer["choices"][0]["text"]))  # type: ignore[index]


if __name__ == "__main__":
    main()
