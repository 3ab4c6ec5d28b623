"""How sure Whisper is of each clip of audio case files, and what the confidence check
(voice/confidence.py) would turn away at several thresholds: the figures the thresholds
were chosen from (on dev sets only; docs/judgement.md, "Transcript confidence" and "Too
noisy to act on").

    python -m robovoice.voice.confidence_eval tests/data/eval/audio.jsonl tests/data/eval/audio-dev-unsure.jsonl
    python -m robovoice.voice.confidence_eval FILES --second DIR   # a second Whisper model's opinion too

Each clip with the wake word is transcribed whole, as the pipeline transcribes a command
(Whisper tiny.en, the sim robot's tool hint, word scores on). Clips are counted as
commands (the case expects a tool call), unintelligible (class ``unintelligible``) or other
speech (negations, mentions, questions: no call expected, but clearly said). The speech-to-noise
estimate is taken on the clip's first utterance as the endpointer cuts it (Silero VAD, the
default settings), as the pipeline takes it. Prints one JSON line per clip, then the sweep.
`--second DIR`: each clip is also transcribed by the CTranslate2 Whisper model in DIR (e.g.
Whisper base), and the sweep says which clips tiny.en is unsure or in doubt of where the
second model hears the same words.
"""

from __future__ import annotations

import argparse
import json
import re
from collections.abc import Sequence
from typing import Any

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, convert
from robovoice.audio.level import speech_to_noise_db
from robovoice.audio.stt import WhisperTranscriber
from robovoice.audio.wav import read_wav
from robovoice.eval.cases import load_cases
from robovoice.llm.base import ToolSpec
from robovoice.voice.confidence import mean_word_probability
from robovoice.voice.utterance import strip_wake_words
from robovoice.voice.vocabulary import command_hint

LOGPROB_THRESHOLDS = (-0.8, -0.7, -0.6, -0.55, -0.5, -0.4)
SNR_THRESHOLDS = (4.0, 5.0, 6.0, 7.0, 8.0)
WORD_THRESHOLDS = (0.3, 0.5, 0.6)


def sim_hint() -> str:
    """The speech-to-text hint the pipeline builds from the sim robot's tools."""
    from robovoice.sim import NODE_NAMES
    from robovoice.sim.node import load_manifest

    specs = [ToolSpec(t["name"], t["description"], t.get("parameters", {}))
             for node in NODE_NAMES for t in load_manifest(node).get("tools", [])]
    return command_hint("hey jarvis", specs)


def first_utterance_snr(audio: AudioChunk) -> float | None:
    """`speech_to_noise_db` of the first utterance the endpointer cuts from `audio`."""
    from robovoice.audio.vad import Endpointer, EndpointerConfig, SpeechEnded
    from robovoice.voice.speculate_eval import VAD_FRAME, probabilities

    endpointer = Endpointer(EndpointerConfig())
    for k, probability in enumerate(probabilities(audio)):
        frame = audio.samples[k * VAD_FRAME : (k + 1) * VAD_FRAME]
        for event in endpointer.update(float(probability), frame, k * VAD_FRAME / audio.format.rate):
            if isinstance(event, SpeechEnded):
                return speech_to_noise_db(event.audio)
    ended = [e for e in endpointer.flush() if isinstance(e, SpeechEnded)]
    return speech_to_noise_db(ended[0].audio) if ended else None


def same_words(a: str, b: str) -> bool:
    """Two transcripts say the same words (case, punctuation and the wake phrase aside)."""
    def said(text: str) -> list[str]:
        return re.findall(r"[a-z0-9']+", strip_wake_words(text).lower())
    return bool(said(a)) and said(a) == said(b)


def score_clips(paths: Sequence[str], second: str | None = None) -> list[dict[str, Any]]:
    from pathlib import Path

    stt, hint, rows = WhisperTranscriber(word_scores=True), sim_hint(), []
    other = WhisperTranscriber(second) if second else None
    for path in paths:
        for case in load_cases(Path(path)):
            if case.audio is None or not case.wake:
                continue
            audio = convert(read_wav(case.audio), MODEL_FORMAT)
            heard = stt.transcribe(audio, hint)
            snr = first_utterance_snr(audio)
            assert heard.confidence is not None
            command = strip_wake_words(heard.text)
            kind = "command" if case.expect else "unintelligible" if case.case_class == "unintelligible" else "other"
            row = {"id": case.id, "kind": kind, "text": heard.text,
                   "avg_logprob": round(heard.confidence.avg_logprob, 3),
                   "mean_word_probability": mean_word_probability(heard.confidence, command),
                   "no_speech": round(heard.confidence.no_speech_prob, 3),
                   "snr_db": None if snr is None else round(snr, 1)}
            if other is not None:
                again = other.transcribe(audio, hint)
                assert again.confidence is not None
                row |= {"second": again.text, "second_logprob": round(again.confidence.avg_logprob, 3),
                        "second_s": round(again.inference_s, 2), "agree": same_words(heard.text, again.text)}
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
    out += [line(f"speech to noise < {t} dB", lambda r, t=t: r.get("snr_db") is not None and r["snr_db"] < t)
            for t in SNR_THRESHOLDS]
    if rows and "agree" in rows[0]:  # the clips a second model's same words would lift out of doubt
        out += [line(f"< {t}, the second agrees", lambda r, t=t: r["avg_logprob"] < t and r["agree"])
                for t in (-0.6, -0.4)]
        out += [line(f"< {t}, the second does not", lambda r, t=t: r["avg_logprob"] < t and not r["agree"])
                for t in (-0.6, -0.4)]
    return out


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", help="audio case files (JSON Lines)")
    parser.add_argument("--second", help="a second CTranslate2 Whisper model directory to compare with")
    args = parser.parse_args(argv)
    for text in sweep(score_clips(args.files, args.second)):
        print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
