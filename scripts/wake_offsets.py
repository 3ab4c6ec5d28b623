#!/usr/bin/env python3
"""How the wake word's score depends on where the microphone's frames start.

Each audio eval clip with the wake phrase is played at the 8 offsets of one 80 ms frame (0-7
mel hops of 10 ms of leading silence) through `OpenWakeWordDetector` scoring one offset
(openWakeWord's own) and all 8 (`phases=8`, the default); the clips without it at offset 0.
Prints, per detector and threshold, the clip-offsets that do not wake and the clips that miss
at some offset, and the highest score of a clip without the phrase (docs/voice.md "Wake word
at every offset"). Unintelligible clips (ids with "garbled", sets with "unsure") are left out.

    python scripts/wake_offsets.py tests/data/eval/audio.jsonl tests/data/eval/audio-test.jsonl
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from robovoice.audio.wake import OpenWakeWordDetector
from robovoice.audio.wav import read_wav

MEL_HOP = 160  # samples


def peak(detector: OpenWakeWordDetector, samples: np.ndarray) -> float:
    detector.reset()
    return max(detector.process(samples[i : i + 1280]) for i in range(0, len(samples) - 1279, 1280))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("sets", nargs="+", type=Path, help="audio eval case files (.jsonl)")
    parser.add_argument("--thresholds", type=float, nargs="+", default=[0.5, 0.6])
    args = parser.parse_args(argv)
    detectors = {"one offset": OpenWakeWordDetector(phases=1), "8 offsets": OpenWakeWordDetector(phases=8)}
    wake: dict[str, dict[str, list[float]]] = {name: {} for name in detectors}
    quiet: dict[str, list[float]] = {name: [] for name in detectors}
    for path in args.sets:
        if "unsure" in path.name:
            continue
        for line in path.read_text(encoding="utf-8").splitlines():
            case = json.loads(line)
            if "garbled" in case["id"]:
                continue
            samples = read_wav(path.parent / case["audio"]).samples
            for name, detector in detectors.items():
                if case.get("wake", True):
                    shifted = [np.concatenate((np.zeros(h * MEL_HOP, np.int16), samples)) for h in range(8)]
                    wake[name][case["id"]] = [peak(detector, s) for s in shifted]
                else:
                    quiet[name].append(peak(detector, samples))
            print(case["id"], file=sys.stderr, end="\r")
    for name in detectors:
        peaks = wake[name]
        for threshold in args.thresholds:
            offsets = sum(p < threshold for clip in peaks.values() for p in clip)
            clips = sum(min(clip) < threshold for clip in peaks.values())
            print(f"{name}, threshold {threshold}: {offsets}/{8 * len(peaks)} clip-offsets do not wake; "
                  f"{clips}/{len(peaks)} clips miss at some offset")
        print(f"{name}: highest score of the {len(quiet[name])} clips without the wake phrase "
              f"{max(quiet[name], default=0.0):.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
