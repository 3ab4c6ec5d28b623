"""Replay the actuation calls of stored eval runs through the fit check (`assistant/fit.py`)
with the sim robot's declared words, and through the check that a listed argument was said
(`fit.unsaid`): how many wanted calls each would refuse, and how many unwanted ones. No model
runs; the calls are those the runs made.

    python scripts/fit_replay.py RUN.json [RUN.json ...]     # runs of `robovoice eval --json`

Cases are looked up by id in tests/data/eval/text*.jsonl. A call counts as wanted when its
tool is among the case's expected tools; calls the reading already refused are left out.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from robovoice.assistant.fit import fits, fitting_tools, unsaid
from robovoice.assistant.intent import read_request
from robovoice.manifest.loader import load_manifest_dir

ROOT = Path(__file__).resolve().parents[1]


def _tools() -> dict[str, Any]:
    loaded = load_manifest_dir(ROOT / "src/robovoice/sim/manifests")
    return {tool.name: tool for item in loaded.manifests.values() for tool in item.manifest.tools}


def _declared(tools: dict[str, Any]) -> dict[str, tuple[str, ...]]:
    return {name: tool.voice.words for name, tool in tools.items() if tool.voice is not None and tool.voice.words}


def main(runs: list[str]) -> None:
    tools = _tools()
    declared = _declared(tools)
    cases = {}
    for path in sorted((ROOT / "tests/data/eval").glob("text*.jsonl")):
        for line in path.read_text(encoding="utf-8").splitlines():
            if line.strip():
                case = json.loads(line)
                cases[case["id"]] = case
    counts = {"wanted, fits": 0, "wanted, refused": 0, "unwanted, fits": 0, "unwanted, refused": 0,
              "wanted, argument unsaid": 0, "unwanted, argument unsaid": 0}
    seen = set()
    for run in runs:
        for result in json.loads(Path(run).read_text(encoding="utf-8"))["results"]:
            case = cases.get(result["id"])
            if case is None or "text" not in case:
                continue
            intent = read_request(case["text"])
            wanted = {e["tool"] for candidate in [case.get("expect", []), *case.get("expect_any", [])]
                      for e in candidate}
            for call in result["calls"]:
                key = (result["id"], call["tool"], json.dumps(call["args"], sort_keys=True))
                if (call["tool"] not in declared or call.get("error") == "not_requested"
                        or intent.refusal is not None or key in seen):
                    continue
                seen.add(key)
                fit = fits(intent, call["tool"], declared[call["tool"]], call["args"])
                label = ("wanted" if call["tool"] in wanted else "unwanted") + (", fits" if fit else ", refused")
                counts[label] += 1
                tool = tools[call["tool"]]
                missing = unsaid(tool.description, tool.parameters or {}, call["args"], intent.words()) if fit else []
                if missing:
                    label = ("wanted" if call["tool"] in wanted else "unwanted") + ", argument unsaid"
                    counts[label] += 1
                    print(f"{label:26} {result['id']:18} {call['tool']}{call['args']}  {case['text']!r}")
                    continue
                if label in ("wanted, refused", "unwanted, fits", "unwanted, refused"):
                    others = fitting_tools(intent, declared, call["tool"])
                    print(f"{label:18} {result['id']:18} {call['tool']}{call['args']}  {case['text']!r}  "
                          f"fits: {others}")
    print(json.dumps(counts))


if __name__ == "__main__":
    main(sys.argv[1:])
