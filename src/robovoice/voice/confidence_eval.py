"""How sure Whisper is of each clip of audio case files, and what the confidence check
(voice/confidence.py) would turn away at several thresholds: the figures the threshold
was chosen from (on dev sets only; docs/judgement.md, "Transcript confidence").

    python -m robovoice.voice.confidence_eval tests/data/eval/audio.jsonl tests/data/eval/audio-dev-unsure.jsonl

Each clip with the wake word is transcribed whole, as the pipeline transcribes a command
(Whisper tiny.en, the sim robot's tool hint, word scores on). Clips are counted as
commands (the case expects a tool call), unintelligible (class ``unintelligible``) or other
speech (negations, mentions, questions: no call expected, but clearly said). Prints one JSON
line per clip, then the sweep.
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Sequence
from typing import Any

from robovoice.audio.stt import WhisperTranscriber
from robovoice.audio.wav import read_wav
from robovoice.eval.cases import load_cases
from robovoice.llm.base import ToolSpec
from robovoice.voice.confidence import mean_word_probability
from robovoice.voice.utterance import strip_wake_words
from robovoice.voice.vocabulary import command_hint

LOGPROB_THRESHOLDS = (-0.8, -0.7, -0.6, -0.55, -0.5, -0.4)
WORD_THRESHOLDS = (0.3, 0.5, 0.6)


def sim_hint() -> str:
    """The speech-to-text hint the pipeline builds from the sim robot's tools."""
    from robovoice.sim import NODE_NAMES
    from robovoice.sim.node import load_manifest

    specs = [ToolSpec(t["name"], t["description"], t.get("parameters", {}))
             for node in NODE_NAMES for t in load_manifest(node).get("tools", [])]
    return command_hint("hey jarvis", specs)


def score_clips(paths: Sequence[str]) -> list[dict[str, Any]]:
    from pathlib import Path

    stt, hint, rows = WhisperTranscriber(word_scores=True), sim_hint(), []
    for path in paths:
        for case in load_cases(Path(path)):
            if case.audio is None or not case.wake:
                continue
            heard = stt.transcribe(read_wav(case.audio), hint)
            assert heard.confidence is not None
            command = strip_wake_words(heard.text)
            kind = "command" if case.expect else "unintelligible" if case.case_class == "unintelligible" else "other"
            row = {"id": case.id, "kind": kind, "text": heard.text,
                   "avg_logprob": round(heard.confidence.avg_logprob, 3),
                   "mean_word_probability": mean_word_probability(heard.confidence, command),
                   "no_speech": round(heard.confidence.no_speech_prob, 3)}
            print(json.dumps(row), flush=True)
            rows.append(row)
    return rows


def sweep(rows: Sequence[dict[str, Any]]) -> list[str]:
    """One line per rule: how many clips of each kind it turns away."""
    def line(name: str, away: Any) -> str:
        parts = []
        for kind in ("command", "unintelligible", "other"):
            of_kind = [r for r in rows if r["kind"] == kind]
            gone = [r["id"] for r in of_kind if away(r)]
            parts.append(f"{kind} {len(gone)}/{len(of_kind)} {gone}")
        return f"{name:32} " + "  ".join(parts)

    out = [line(f"avg_logprob < {t}", lambda r, t=t: r["avg_logprob"] < t) for t in LOGPROB_THRESHOLDS]
    out += [line(f"mean word probability < {t}", lambda r, t=t: (r["mean_word_probability"] or 1.0) < t)
            for t in WORD_THRESHOLDS]
    return out


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", help="audio case files (JSON Lines)")
    args = parser.parse_args(argv)
    for text in sweep(score_clips(args.files)):
        print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
