"""Measure the embedded model's first decision: answer (``message:``) or call a tool (``functions.``).

For every text case of an evaluation file, plus a few spoken phrasings and some chit-chat, the
prompt is rendered exactly as the assistant's first model step renders it (system prompt, the
sim robot's tools, the user's words) and `LocalLlamaBackend.decide_head` reports the margin:
the logit of the best call-head token minus that of the best message-head token, untilted.
A positive margin means the model calls a tool; ``tool_bias`` b makes it call one whenever
margin > -b. Prints one line per input and the range of biases that separate the two groups.

    .venv/bin/python scripts/measure_head_margin.py [tests/data/eval/text.jsonl] [--json]
"""

from __future__ import annotations

import argparse
import asyncio
import json
import math
from pathlib import Path

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.prompt import SYSTEM_PROMPT
from robovoice.config import RobotConfig
from robovoice.eval.cases import load_cases
from robovoice.llm.base import ChatMessage
from robovoice.llm.local import LocalLlamaBackend

# Phrasings of the spoken evaluation (tool expected) and chit-chat (no tool expected).
EXTRA: list[tuple[str, str, bool]] = [
    ("audio-battery", "how much battery do you have left?", True),
    ("audio-pose", "where are you right now?", True),
    ("audio-camera", "what can you see?", True),
    ("audio-targets", "which places do you know?", True),
    ("talk-hello", "Hello!", False),
    ("talk-thanks", "Thank you", False),
    ("talk-how", "How are you today?", False),
    ("talk-name", "What is your name?", False),
    ("talk-joke", "Tell me a joke", False),
]


async def measure(path: Path) -> list[dict[str, object]]:
    inputs = [(c.id, c.text or "", bool(c.expect)) for c in load_cases(path) if c.text is not None]
    inputs += EXTRA
    async with connect_robot(RobotConfig(address="sim://")) as link:
        specs = await link.tools.specs()
    backend = LocalLlamaBackend(tool_bias=0.0)
    rows: list[dict[str, object]] = []
    try:
        await backend.warm_up(SYSTEM_PROMPT, specs)
        for case_id, text, wants_tool in inputs:
            decision = await backend.decide_head(
                [ChatMessage("system", SYSTEM_PROMPT), ChatMessage("user", text)], specs
            )
            head = decision.head.tool.name if decision.head.tool else "message"
            rows.append({"id": case_id, "text": text, "tool_expected": wants_tool,
                         "margin": round(decision.margin, 3), "head": head})
    finally:
        await backend.aclose()
    return rows


def summary(rows: list[dict[str, object]]) -> str:
    tool = sorted(float(r["margin"]) for r in rows if r["tool_expected"])  # type: ignore[arg-type]
    chat = sorted(float(r["margin"]) for r in rows if not r["tool_expected"])  # type: ignore[arg-type]
    lines = [f"tool expected: {len(tool)} inputs, margin min {tool[0]:+.2f}, median {tool[len(tool) // 2]:+.2f}",
             f"no tool:       {len(chat)} inputs, margin max {chat[-1]:+.2f}, median {chat[len(chat) // 2]:+.2f}"]
    # A bias b >= 0 turns a margin m into a call when m + b > 0. No-tool inputs the model already
    # calls a tool for (m > 0) cannot be helped by any b >= 0; among the others, b separates the
    # groups when -min(tool) < b <= -max(no tool, m <= 0).
    lost = [r["id"] for r in rows if not r["tool_expected"] and float(r["margin"]) > 0]  # type: ignore[arg-type]
    quiet = [m for m in chat if m <= 0]
    low, high = max(0.0, -tool[0]), -quiet[-1] if quiet else float("inf")
    lines.append(f"no-tool inputs that call a tool at any bias >= 0: {lost or '-'}")
    if low < high:
        lines.append(f"separable: any tool_bias in ({low:+.2f}, {high:+.2f}], midpoint {(low + high) / 2:+.2f}")
    else:
        lines.append(f"not separable: {low:+.2f} >= {high:+.2f}")
    for bias in (0.0, 1.0, 1.3, 2.0, 3.0):
        missed = [r["id"] for r in rows if r["tool_expected"] and float(r["margin"]) + bias <= 0]  # type: ignore[arg-type]
        extra = [r["id"] for r in rows if not r["tool_expected"] and float(r["margin"]) + bias > 0]  # type: ignore[arg-type]
        lines.append(f"tool_bias {bias:+.1f}: tool skipped {missed or '-'}; tool called needlessly {extra or '-'}")
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file", type=Path, nargs="?", default=Path("tests/data/eval/text.jsonl"))
    parser.add_argument("--json", action="store_true", help="one JSON object per input instead of a table")
    args = parser.parse_args()
    rows = asyncio.run(measure(args.file))
    for row in sorted(rows, key=lambda r: float(r["margin"])):  # type: ignore[arg-type]
        if args.json:
            print(json.dumps(row))
        else:
            flag = "tool" if row["tool_expected"] else "----"
            wrong = "" if (float(row["margin"]) > 0) == row["tool_expected"] else "  <- wrong at bias 0"  # type: ignore[arg-type]
            if math.isnan(float(row["margin"])):  # type: ignore[arg-type]
                wrong = "  (no margin)"
            print(f"{float(row['margin']):+7.2f}  {flag}  {row['head']:<24} {row['id']:<16} {row['text']}{wrong}")  # type: ignore[arg-type]
    if not args.json:
        print(summary(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
