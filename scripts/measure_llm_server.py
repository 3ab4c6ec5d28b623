"""Measure an OpenAI-compatible server recipe of docs/llm.md: first token and full turn.

    .venv/bin/python scripts/measure_llm_server.py chatml-function-calling   # starts the server itself
    .venv/bin/python scripts/measure_llm_server.py gguf-template
    .venv/bin/python scripts/measure_llm_server.py llama-server    # llama.cpp's C++ server (build_llama_server.sh)
    .venv/bin/python scripts/measure_llm_server.py --url http://127.0.0.1:8080/v1 --model qwen  # one running

Runs dev cases (tests/data/eval/text.jsonl, never the frozen test set) through `robovoice eval`
with the sim robot, one conversation per case, and prints per case: first token, first sentence
and finished (ms from the text arriving), then the cold first case and the median of the rest
(the server has cached the system prompt and tools by then). The load average goes with it.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from robovoice.llm.llama_server import MODEL_ALIAS, MODES, running_server

ROOT = Path(__file__).resolve().parent.parent
CASES = ("nav-kitchen-2", "battery-1", "proj-on-1", "chat-1", "dock-1")
STAGES = ("first_token", "first_sentence", "finished")
CONFIG = '[[llm.backends]]\nurl = "{url}"\nmodel = "{model}"\nkind = "local-cpu"\nfirst_token_s = 300\n'


def loadavg() -> str:
    return Path("/proc/loadavg").read_text().strip()


def measure(url: str, model: str, cases: list[str], folder: Path) -> dict[str, object]:
    config = folder / "robovoice.toml"
    config.write_text(CONFIG.format(url=url, model=model))
    only = [arg for case in cases for arg in ("--only", case)]
    command = [sys.executable, "-m", "robovoice.cli", "eval", str(ROOT / "tests/data/eval/text.jsonl"),
               "--config", str(config), "--json", "--quiet", *only]
    before = loadavg()
    done = subprocess.run(command, capture_output=True, text=True, check=False, timeout=3600)
    if done.returncode != 0:
        raise SystemExit(f"robovoice eval failed ({done.returncode}):\n{done.stderr[-3000:]}")
    report = json.loads(done.stdout)
    rows = [{"id": r["id"], "passed": r["passed"], **{s: r["latency_ms"].get(s) for s in STAGES}}
            for r in report["results"]]
    warm = rows[1:]  # eval runs the cases in file order: the first one found the server cold

    def median(stage: str) -> float | None:
        values = [float(r[stage]) for r in warm if r[stage] is not None]
        return round(statistics.median(values)) if values else None

    return {"cases": rows, "cold": rows[0], "warm_median_ms": {s: median(s) for s in STAGES},
            "passed": report["passed"], "of": report["cases"], "loadavg_before": before, "loadavg_after": loadavg()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("mode", nargs="?", choices=list(MODES),
                        help="start the server of this recipe (llama_server.MODES)")
    parser.add_argument("--url", help="measure a server already running here instead")
    parser.add_argument("--model", default=MODEL_ALIAS, help="the model name for --url")
    parser.add_argument("--cases", default=",".join(CASES), help="dev case ids, comma-separated")
    args = parser.parse_args()
    if (args.mode is None) == (args.url is None):
        parser.error("give a mode (to start the server) or --url (a running one)")
    cases = [c for c in args.cases.split(",") if c]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        if args.url:
            result = measure(args.url, args.model, cases, folder)
        else:
            with running_server(args.mode, log_path=folder / "server.log") as url:
                result = measure(url, MODEL_ALIAS, cases, folder)
    print(json.dumps({"server": args.url or args.mode, **result}, indent=1))


if __name__ == "__main__":
    main()
