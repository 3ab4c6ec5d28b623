"""What a change to the reading changes: every eval text read before and after, and the differences.

The check before acting (`assistant/intent.py`, `assistant/gate.py`) is plain code over words, so a
rule written for one phrasing can change how others read. This reads every text of every case file
under tests/data/eval (and the spoken texts of the clip specs, the wake phrase taken off) with the
`robovoice` on the path, and writes one entry per text: its clauses, its steps, and the gate's
verdict on each of the sim robot's actuation calls (every place, every contact, the projector on
and off, the dock, the stop, the cancel, the end of a call) as if the model had made it.
`compare` lists the texts whose reading or verdicts differ between two such dumps, with their case
ids, so each change can be checked by hand.

    PYTHONPATH=<old worktree>/src python scripts/reading_diff.py dump old.json
    python scripts/reading_diff.py dump new.json
    python scripts/reading_diff.py compare old.json new.json
"""

from __future__ import annotations

import argparse
import json
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
_WAKE = re.compile(r"^\s*hey,? jarvis[,.!]?\s*", re.IGNORECASE)


def texts(skip: Sequence[str] = ()) -> dict[str, list[str]]:
    """Every text, with the ids of the cases that say it; `skip`: file stems left out (a blind set
    not yet run, whose texts nobody may read before its first run)."""
    found: dict[str, list[str]] = {}
    for path in sorted((ROOT / "tests" / "data" / "eval").glob("*.jsonl")):
        if path.stem in skip:
            continue
        for line in path.read_text().splitlines():
            case = json.loads(line)
            if isinstance(case.get("text"), str):
                found.setdefault(case["text"], []).append(f"{path.stem}:{case['id']}")
    for path in sorted((ROOT / "scripts").glob("voice_*clips*.json")):
        if path.stem in skip:
            continue
        for clip in json.loads(path.read_text()):
            if isinstance(clip, dict) and isinstance(clip.get("text"), str):
                found.setdefault(_WAKE.sub("", clip["text"]), []).append(f"{path.stem}:{clip['id']}")
    return found


CALLS = [("navigate_to", {"target": p}) for p in ("kitchen", "living room", "bedroom", "bathroom", "hallway",
                                                 "front door", "charging dock")] + \
        [("start_video_call", {"contact": c}) for c in ("Anna", "Ben", "Clara", "Dr. Weber")] + \
        [("set_projector_power", {"on": True}), ("set_projector_power", {"on": False}), ("return_to_dock", {}),
         ("stop_robot", {}), ("cancel_navigation", {}), ("end_video_call", {})]


def _sim_tools() -> tuple[dict[str, Any], dict[str, Any]]:
    from robovoice.llm.base import ToolSpec
    from robovoice.manifest.loader import load_manifest_dir

    loaded = load_manifest_dir(ROOT / "src" / "robovoice" / "sim" / "manifests")
    tools = [tool for item in loaded.manifests.values() for tool in item.manifest.tools]
    return ({t.name: ToolSpec(t.name, t.description, t.parameters or {}) for t in tools},
            {t.name: t.voice for t in tools if t.voice is not None})


def dump(out: Path, skip: Sequence[str] = ()) -> None:
    from robovoice.assistant.gate import refusal
    from robovoice.assistant.intent import read_request

    specs, voice = _sim_tools()
    rows = {}
    for text in texts(skip):
        intent = read_request(text)
        verdicts = {}
        for name, args in CALLS:
            refused = refusal(intent, specs[name], args, (), voice, tools=list(specs.values()))
            verdicts[f"{name}{json.dumps(args)}"] = refused["details"].get("reason", "?") if refused else "runs"
        rows[text] = {"clauses": [[c.text, c.kind.value] for c in intent.clauses],
                      "steps": list(intent.worded_steps), "asks": intent.asks_action, "gate": verdicts}
    out.write_text(json.dumps(rows, indent=0, sort_keys=True))
    print(f"{len(rows)} texts read into {out}")


def compare(old: Path, new: Path) -> None:
    before, after, ids = json.loads(old.read_text()), json.loads(new.read_text()), texts()
    changed = [t for t in after if t in before and before[t] != after[t]]
    let_through = 0
    for text in changed:
        print(f"\n{', '.join(ids.get(text, ['?']))}\n  {text}")
        for side, row in (("before", before[text]), ("after ", after[text])):
            kinds = " | ".join(f"{c[0]} [{c[1]}]" for c in row["clauses"])
            print(f"  {side}: {kinds}\n          steps: {row['steps']}")
        gated, now = before[text].get("gate", {}), after[text].get("gate", {})
        for call in sorted(k for k in now if gated.get(k) != now[k]):
            let_through += now[call] == "runs"
            print(f"  gate: {call}: {gated.get(call)} -> {now[call]}")
    print(f"\n{len(changed)} of {len(after)} texts read or gated differently; {let_through} calls now let through")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    one = sub.add_parser("dump")
    one.add_argument("out", type=Path)
    # (extend: "--skip a --skip b" leaves out both; with a plain list only the last one was left out)
    one.add_argument("--skip", nargs="+", action="extend", default=[],
                     help="file stems to leave out (blind sets not yet run)")
    both = sub.add_parser("compare")
    both.add_argument("old", type=Path)
    both.add_argument("new", type=Path)
    ns = parser.parse_args()
    if ns.command == "dump":
        dump(ns.out, ns.skip)
    else:
        compare(ns.old, ns.new)


if __name__ == "__main__":
    main()
