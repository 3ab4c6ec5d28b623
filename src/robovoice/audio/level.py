"""How loud an utterance's speech is against the noise around it (issue 11, docs/judgement.md
"Too noisy to act on").

The voice activity detector cuts an utterance with a little audio on either side of the
speech (`EndpointerConfig.pre_roll_s` before its onset, `post_roll_s` of the silence after it),
and that audio is the room's noise just before and after the words. `speech_to_noise_db`
compares the louder half of the frames in between (the words) with the quieter of the two
edges: one edge can hold speech (an onset found late, a stream that began mid-word), and the
quieter one is then the noise. It is an estimate, not the mixing SNR of a test clip: on the
dev clips it reads about 2-4 dB above it for stationary noise and close to it for babble
(docs/judgement.md has the table).
"""

from __future__ import annotations

import math

import numpy as np

from robovoice.audio.format import AudioChunk

FRAME_S = 0.02
HEAD_S = 0.2  # of the 0.3 s pre-roll: the onset is detected a little after the words begin
TAIL_S = 0.15  # of the 0.2 s post-roll
CLEAN_DB = 99.0  # digital silence around the words: nothing to measure noise by
_SILENT = 1.0  # mean square (int16 units) below which the edges are digital silence


def speech_to_noise_db(chunk: AudioChunk) -> float | None:
    """The speech-to-noise ratio of a VAD utterance in dB, `CLEAN_DB` when the audio around the
    words is digitally silent, None when the utterance is too short to tell."""
    samples = np.asarray(chunk.samples, dtype=np.float64)
    if samples.ndim > 1:
        samples = samples.mean(axis=1)
    if chunk.format.width == 4:  # float32 in [-1, 1]
        samples = samples * 32768.0  # the same units as int16 audio, for `_SILENT`
    n = max(1, round(chunk.format.rate * FRAME_S))
    count = len(samples) // n
    energy = (samples[: count * n].reshape(count, n) ** 2).mean(axis=1)
    head, tail = round(HEAD_S / FRAME_S), round(TAIL_S / FRAME_S)
    body = energy[head : count - tail]
    if len(body) < 5:
        return None
    noise = float(min(energy[:head].mean(), energy[count - tail :].mean()))
    if noise < _SILENT:
        return CLEAN_DB
    words = float(np.sort(body)[len(body) // 2 :].mean())
    return 10.0 * math.log10(max(words - noise, 1e-9) / noise)
