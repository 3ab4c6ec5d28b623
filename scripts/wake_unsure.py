#!/usr/bin/env python3
"""What unsure wake words (docs/voice.md "Unsure wake words") would do on long recordings.

Each WAV (16 kHz mono, e.g. from ``scripts/make_audio_fixtures.py --negative-minutes 15``) is
scored by the wake model at 8 offsets through the decider with the default thresholds; for
each detection, 1.6 s before it to 4 s after is transcribed as a command is (Whisper tiny.en,
the sim robot's hint) and checked with `names_robot`. Prints one JSON line per detection and,
per floor, how many unsure detections there were and how many named the robot: on audio
without the wake phrase, every one that names it would have been a false wake.

    python scripts/wake_unsure.py out/negative.wav out/negative-8.wav
"""

from __future__ import annotations

import argparse
import json

from robovoice.audio.format import MODEL_FORMAT, AudioChunk
from robovoice.audio.stt import WhisperTranscriber
from robovoice.audio.wake import OpenWakeWordDetector, WakeDecider, WakeWordSpotter
from robovoice.audio.wav import read_wav
from robovoice.voice.confidence_eval import sim_hint
from robovoice.voice.config import PipelineConfig
from robovoice.voice.utterance import WAKE_LOOKBACK_S, names_robot

AFTER_S = 4.0
FLOORS = (0.1, 0.15, 0.2, 0.3)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("wavs", nargs="+", help="16 kHz mono WAV files")
    args = parser.parse_args()
    stt, hint, rows = WhisperTranscriber(), sim_hint(), []
    for path in args.wavs:
        audio = read_wav(path)
        if audio.format != MODEL_FORMAT:
            parser.error(f"{path}: {audio.format}; give 16 kHz mono 16-bit audio")
        samples, rate = audio.samples, MODEL_FORMAT.rate
        spotter = WakeWordSpotter(OpenWakeWordDetector(phases=8), WakeDecider(PipelineConfig.from_config().wake))
        for event in spotter.feed(AudioChunk(samples, MODEL_FORMAT)):  # as the pipeline frames it
            lo = max(0, round((event.timestamp - WAKE_LOOKBACK_S) * rate))
            hi = round((event.timestamp + AFTER_S) * rate)
            text = stt.transcribe(AudioChunk(samples[lo:hi], MODEL_FORMAT), hint).text
            row = {"file": path, "at": round(event.timestamp, 2), "score": round(event.score, 3), "sure": event.sure,
                   "names_robot": names_robot(text), "text": text}
            print(json.dumps(row), flush=True)
            rows.append(row)
    for floor in FLOORS:
        unsure = [r for r in rows if not r["sure"] and r["score"] >= floor]
        print(f"floor {floor}: {len(unsure)} unsure, {sum(r['names_robot'] for r in unsure)} naming the robot; "
              f"{sum(r['sure'] for r in rows)} sure")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
