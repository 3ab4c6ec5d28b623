#!/usr/bin/env python3
"""Check a blind pair of case sets against scripts/blind/brief.md before it is frozen.

    python3 scripts/blind/check_set.py N M      # text-test-N.jsonl, audio-test-M.jsonl + its clip specs

Prints every problem found (file, case id, what is wrong) and exits 1, or prints OK. Standard
library only: the writer of a blind set runs it without the project installed.
"""

from __future__ import annotations

import json
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EVAL = ROOT / "tests" / "data" / "eval"
ACTUATION = ("navigate_to", "cancel_navigation", "return_to_dock", "stop_robot", "set_projector_power",
             "start_video_call", "end_video_call")
LOOKUPS = ("get_navigation_targets", "list_contacts", "get_battery_state", "get_robot_pose", "get_camera_image")
PLACES = {"kitchen", "living room", "bedroom", "bathroom", "hallway", "front door", "charging dock"}
CONTACTS = {"anna", "ben", "clara", "dr. weber", "weber", "dr weber", "doctor weber"}
SETUPS = {"driving", "in_call", "projector_on"}
TEXT_CLASSES = {"single": 14, "compound": 14, "negated": 10, "mention": 8, "ability": 8, "chat": 6}
AUDIO_CLASSES = {"single": 8, "compound": 6, "negated": 3, "mention": 3, "ability": 2, "nowake": 3, "stop": 2,
                 "unintelligible": 5}
NO_ACTION = {"negated", "mention", "ability", "chat", "nowake", "unintelligible"}
ESPEAK = {"en-us", "en-gb-x-rp", "en-gb-scotland", "en-029", "en-gb-x-gbclan", "en-us+f3", "en-gb+f4"}
NOISES = {"white", "pink", "babble"}


def _values(value: object) -> list[str]:
    return [v.strip().lower() for v in (value if isinstance(value, list) else [value]) if isinstance(v, str)]


def _check_call(call: object, where: str, problems: list[str]) -> None:
    if not isinstance(call, dict) or "tool" not in call:
        problems.append(f"{where}: a call must be an object with 'tool'")
        return
    tool, args = call["tool"], call.get("args", {})
    if tool in LOOKUPS:
        problems.append(f"{where}: {tool} is a look-up; look-ups are never expected")
    elif tool not in ACTUATION:
        problems.append(f"{where}: unknown tool {tool!r}")
    if tool == "navigate_to" and not set(_values(args.get("target"))) <= PLACES:
        problems.append(f"{where}: navigate_to target {args.get('target')!r} is not a known reachable place")
    if tool == "start_video_call" and not set(_values(args.get("contact"))) <= CONTACTS:
        problems.append(f"{where}: contact {args.get('contact')!r} is not Anna, Ben, Clara or Dr. Weber")
    if tool == "set_projector_power" and not isinstance(args.get("on"), bool):
        problems.append(f"{where}: set_projector_power needs args.on true or false")


def check_cases(path: Path, prefix: str, classes: dict[str, int], audio: bool) -> tuple[list[str], list[dict]]:
    problems: list[str] = []
    if not path.exists():
        return [f"{path}: missing"], []
    rows = []
    for n, line in enumerate(path.read_text().splitlines(), 1):
        try:
            rows.append(json.loads(line))
        except json.JSONDecodeError as exc:
            problems.append(f"{path.name}:{n}: not JSON ({exc})")
    counts = Counter(r.get("class") for r in rows)
    if dict(counts) != classes:
        problems.append(f"{path.name}: class counts {dict(counts)}, the brief asks {classes}")
    seen: Counter[str] = Counter()
    three_steps = 0
    for r in rows:
        cls, rid = r.get("class"), r.get("id", "?")
        seen[cls] += 1
        if rid != f"{prefix}-{cls}-{seen[cls]}":
            problems.append(f"{path.name}: id {rid!r} should be {prefix}-{cls}-{seen[cls]}")
        where = f"{path.name} {rid}"
        if audio:
            if r.get("audio") != f"{path.stem}/{rid}.wav":
                problems.append(f"{where}: audio should be {path.stem}/{rid}.wav")
            if r.get("wake") is not (cls != "nowake"):
                problems.append(f"{where}: wake should be {cls != 'nowake'}")
            if "text" in r:
                problems.append(f"{where}: an audio case has no 'text' (it goes in the clip spec)")
        elif not isinstance(r.get("text"), str) or not r["text"].strip():
            problems.append(f"{where}: needs a non-empty text")
        expect = r.get("expect")
        if not isinstance(expect, list):
            problems.append(f"{where}: expect must be a list")
            continue
        candidates = [expect, *r.get("expect_any", [])]
        for c in candidates:
            for call in c:
                _check_call(call, where, problems)
        if cls in NO_ACTION and (expect or r.get("expect_any")):
            problems.append(f"{where}: a {cls} case expects no action")
        if cls == "compound" and not 2 <= len(expect) <= 3:
            problems.append(f"{where}: a compound case has 2 or 3 steps")
        if cls == "compound" and len(expect) == 3:
            three_steps += 1
        if cls in ("single", "stop") and min(len(c) for c in candidates) != 1:
            problems.append(f"{where}: a {cls} case expects one action (a stop before a new drive only as a candidate)")
        if cls == "stop" and (expect != [{"tool": "stop_robot"}] or r.get("setup") != "driving"):
            problems.append(f"{where}: a stop case expects stop_robot with setup 'driving'")
        right = {call["tool"] for c in candidates for call in c if isinstance(call, dict) and "tool" in call}
        want = sorted(set(ACTUATION) - right, key=ACTUATION.index)
        if sorted(r.get("forbid", []), key=lambda t: ACTUATION.index(t) if t in ACTUATION else 99) != want:
            problems.append(f"{where}: forbid should be exactly {want}")
        setup = r.get("setup")
        parts = set(setup.split("+")) if isinstance(setup, str) else set()
        if setup is not None and not parts <= SETUPS:
            problems.append(f"{where}: setup {setup!r}: use driving, in_call, projector_on, joined by '+'")
        tools = [call.get("tool") for call in expect if isinstance(call, dict)]
        if "end_video_call" in tools and "in_call" not in parts and "start_video_call" not in tools:
            problems.append(f"{where}: ending a call needs setup in_call")
        if {"cancel_navigation", "stop_robot"} & set(tools) and "driving" not in parts \
                and not {"navigate_to", "return_to_dock"} & set(tools[:1]):
            problems.append(f"{where}: a stop or cancel needs setup driving")
        if "return_to_dock" in right and not any(
                call.get("tool") == "navigate_to" and _values(call.get("args", {}).get("target")) == ["charging dock"]
                for c in candidates for call in c if isinstance(call, dict)):
            problems.append(f"{where}: return_to_dock needs the navigate_to charging dock alternative")
        for key in ("persona", "note"):
            if not isinstance(r.get(key), str):
                problems.append(f"{where}: needs a {key}")
    if not audio and three_steps < 3:
        problems.append(f"{path.name}: {three_steps} three-step compound cases, the brief asks at least 3")
    return problems, rows


def check_clips(path: Path, rows: list[dict]) -> list[str]:
    problems: list[str] = []
    if not path.exists():
        return [f"{path}: missing"]
    clips = json.loads(path.read_text())
    if [c.get("id") for c in clips] != [r.get("id") for r in rows]:
        problems.append(f"{path.name}: the clip ids must be the case ids, in the same order")
    classes = {r.get("id"): r.get("class") for r in rows}
    voices = Counter()
    for c in clips:
        cid, text, voice = c.get("id"), c.get("text", ""), c.get("voice", "")
        where = f"{path.name} {cid}"
        kind, _, rest = voice.partition(":")
        voices[kind] += 1
        if kind == "espeak" and rest.split(":")[0] not in ESPEAK:
            problems.append(f"{where}: espeak voice {rest!r} is not one of {sorted(ESPEAK)}")
        elif kind == "piper" and rest and not 0.85 <= float(rest) <= 1.15:
            problems.append(f"{where}: piper speed {rest} outside 0.85-1.15")
        elif kind not in ("piper", "espeak"):
            problems.append(f"{where}: voice {voice!r}: piper[:speed] or espeak:<voice>[:wpm]")
        wake = classes.get(cid) != "nowake"
        if c.get("wake") is not wake:
            problems.append(f"{where}: wake should be {wake}")
        if wake != text.startswith("Hey Jarvis,"):
            problems.append(f"{where}: {'starts' if wake else 'must not start'} with 'Hey Jarvis,'")
        if not wake and "jarvis" in text.lower():
            problems.append(f"{where}: a nowake clip never says the wake name")
        snr, noise = c.get("snr_db"), c.get("noise")
        if (snr is None) != (noise is None) or (noise is not None and noise not in NOISES):
            problems.append(f"{where}: noise is null with snr_db null, or white/pink/babble with an snr_db")
        if classes.get(cid) == "unintelligible":
            if snr is None or not -8 <= snr <= -3:
                problems.append(f"{where}: an unintelligible clip is buried at -8 to -3 dB")
        elif snr is not None and not 10 <= snr <= 24:
            problems.append(f"{where}: snr_db {snr} outside 10-24 for a clip meant to be understood")
        if not 0.4 <= c.get("lead_s", 0) <= 0.9 or not 0.9 <= c.get("tail_s", 0) <= 1.5:
            problems.append(f"{where}: lead_s 0.4-0.9, tail_s 0.9-1.5")
    if not 9 <= voices["piper"] <= 15:
        problems.append(f"{path.name}: {voices['piper']} piper clips, the brief asks about 12")
    return problems


def main(argv: list[str]) -> int:
    if len(argv) != 2 or not all(a.isdigit() for a in argv):
        print(__doc__)
        return 2
    n, m = argv
    problems, _ = check_cases(EVAL / f"text-test-{n}.jsonl", f"v{n}", TEXT_CLASSES, audio=False)
    audio_problems, rows = check_cases(EVAL / f"audio-test-{m}.jsonl", f"t{m}", AUDIO_CLASSES, audio=True)
    problems += audio_problems + check_clips(ROOT / "scripts" / f"voice_test_clips_{m}.json", rows)
    for p in problems:
        print(p)
    print("OK" if not problems else f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
