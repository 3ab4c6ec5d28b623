"""What a change to the reading changes: every eval text read before and after, and the differences.

The check before acting (`assistant/intent.py`) is plain code over words, so a rule written for
one phrasing can change how others read. This reads every text of every case file under
tests/data/eval (and the spoken texts of the clip specs, the wake phrase taken off) with the
`robovoice` on the path, and writes one line per text; `compare` lists the texts whose reading
differs between two such dumps, with their case ids, so each change can be checked by hand.

    PYTHONPATH=<old worktree>/src python scripts/reading_diff.py dump old.json
    python scripts/reading_diff.py dump new.json
    python scripts/reading_diff.py compare old.json new.json
"""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
_WAKE = re.compile(r"^\s*hey,? jarvis[,.!]?\s*", re.IGNORECASE)


def texts() -> dict[str, list[str]]:
    """Every text, with the ids of the cases that say it."""
    found: dict[str, list[str]] = {}
    for path in sorted((ROOT / "tests" / "data" / "eval").glob("*.jsonl")):
        for line in path.read_text().splitlines():
            case = json.loads(line)
            if isinstance(case.get("text"), str):
                found.setdefault(case["text"], []).append(f"{path.stem}:{case['id']}")
    for path in sorted((ROOT / "scripts").glob("voice_*clips*.json")):
        for clip in json.loads(path.read_text()):
            if isinstance(clip, dict) and isinstance(clip.get("text"), str):
                found.setdefault(_WAKE.sub("", clip["text"]), []).append(f"{path.stem}:{clip['id']}")
    return found


def dump(out: Path) -> None:
    from robovoice.assistant.intent import read_request

    rows = {}
    for text in texts():
        intent = read_request(text)
        rows[text] = {"clauses": [[c.text, c.kind.value] for c in intent.clauses],
                      "steps": list(intent.worded_steps), "asks": intent.asks_action}
    out.write_text(json.dumps(rows, indent=0, sort_keys=True))
    print(f"{len(rows)} texts read into {out}")


def compare(old: Path, new: Path) -> None:
    before, after, ids = json.loads(old.read_text()), json.loads(new.read_text()), texts()
    changed = [t for t in after if t in before and before[t] != after[t]]
    for text in changed:
        print(f"\n{', '.join(ids.get(text, ['?']))}\n  {text}")
        for side, row in (("before", before[text]), ("after ", after[text])):
            kinds = " | ".join(f"{c[0]} [{c[1]}]" for c in row["clauses"])
            print(f"  {side}: {kinds}\n          steps: {row['steps']}")
    print(f"\n{len(changed)} of {len(after)} texts read differently")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("dump").add_argument("out", type=Path)
    both = sub.add_parser("compare")
    both.add_argument("old", type=Path)
    both.add_argument("new", type=Path)
    ns = parser.parse_args()
    if ns.command == "dump":
        dump(ns.out)
    else:
        compare(ns.old, ns.new)


if __name__ == "__main__":
    main()
