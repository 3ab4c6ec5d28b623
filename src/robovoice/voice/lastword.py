"""Where the user's last word ends, for latencies measured from it (issue 12).

The VAD ends an utterance at its last voiced frame (`HeardUtterance.end`), but Silero's
recurrent state keeps the speech probability up for a few 32 ms frames after the voice stops:
on the Piper clips the last voiced frame ends ~80 ms after the last sample above -40 dBFS. A
person hears the last word end where the sound does, so `last_word_end` looks, within the last
`SEARCH_S` before the VAD's end, for the last 10 ms window no more than `BELOW_PEAK_DB` below
the utterance's loudest window (on the clean Piper and espeak-ng clips: within 30 ms of the
last sample above -40 dBFS). Only where the quiet after the utterance (the post-roll it
carries) is at least `QUIET_DB` below that threshold: in noise a soft ending cannot be told
from the noise, and the VAD's end is kept. The result is never after the VAD's end, nor more
than `SEARCH_S` before it.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, Float32Array, as_float32

RATE = MODEL_FORMAT.rate
WINDOW = RATE // 100  # 10 ms
SEARCH_S = 0.25  # at most this much before the VAD's end (Silero's hangover is a few frames)
BELOW_PEAK_DB = 40.0
QUIET_DB = 10.0


def _levels_db(x: Float32Array) -> npt.NDArray[np.float64]:
    n = x.shape[0] // WINDOW
    if n == 0:
        return np.zeros(0)
    power = np.mean(np.square(x[: n * WINDOW].reshape(n, WINDOW), dtype=np.float64), axis=1)
    out: npt.NDArray[np.float64] = 10.0 * np.log10(np.maximum(power, 1e-12))
    return out


def last_word_end(audio: AudioChunk, vad_end: float) -> float:
    """The stream time at which the voice in `audio` (an utterance with its post-roll,
    ``audio.timestamp`` its start) stops, at or before the VAD's `vad_end`."""
    if audio.format.rate != RATE or audio.format.channels != 1:
        return vad_end
    x = as_float32(audio.samples)
    end = min(max(round((vad_end - audio.timestamp) * RATE), 0), x.shape[0])
    first = max(end - round(SEARCH_S * RATE), 0)
    voice = _levels_db(x[:end])
    after = _levels_db(x[end:])
    if voice.size == 0 or after.size < 5:
        return vad_end
    threshold = float(voice.max()) - BELOW_PEAK_DB
    if float(np.median(after)) > threshold - QUIET_DB:
        return vad_end  # noise: the tail cannot be told from it
    # windows aligned to the end: the last one ends exactly at the VAD's end
    tail = _levels_db(x[first:end][(end - first) % WINDOW :])
    loud = np.flatnonzero(tail > threshold)
    if loud.size == 0:
        return vad_end
    return float(audio.timestamp + (end - (tail.size - 1 - int(loud[-1])) * WINDOW) / RATE)
