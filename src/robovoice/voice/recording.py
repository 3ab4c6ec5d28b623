"""A session recording anyone can check: what the microphone heard and what the robot played,
side by side in one stereo WAV, in the room's stream time (issue 12).

    room = SimulatedRoom(record=True)
    speech = room.say(read_wav("command.wav"))
    ...                                   # the pipeline runs, the room closes
    write_session("session.wav", room, origin=speech.start)
    latency = reply_latency(read_wav("session.wav"))     # seconds, from the WAV alone

Channel 1 is the microphone (the person, plus the echo of the robot and any noise), channel 2
the robot's speaker, both 16 kHz from stream time `origin` (the start of the input file), so a
16 kHz input lines up sample by sample with channel 1 (other rates are resampled to 16 kHz and
line up in time). The room paces its input in real time and plays the robot's audio from the
moment it reached the speaker (`room.SimulatedRoom`), so the time from the user's last word
to the robot's first sound can be read off with any audio tool, independently of the
pipeline's own clocks; `reply_latency` does just that.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, as_int16, convert
from robovoice.audio.wav import write_wav
from robovoice.errors import AudioError
from robovoice.voice.room import SimulatedRoom

RATE = MODEL_FORMAT.rate
STEREO = MODEL_FORMAT.with_(channels=2)
SILENCE_DBFS = -40.0  # `reply_latency`: a sample quieter than this is silence


def session_audio(room: SimulatedRoom, origin: float) -> AudioChunk:
    """The room's session as a stereo 16 kHz chunk from stream time `origin` (see the module
    docstring). The room must have been made with ``record=True``."""
    heard = room.recording()
    if heard is None:
        raise AudioError("the room recorded nothing: make it with SimulatedRoom(record=True) and run it first")
    first = round((origin - heard.timestamp) * RATE)
    if first < 0:
        raise AudioError(f"origin {origin:.3f} s is before the room's first sample ({heard.timestamp:.3f} s)")
    mic = as_int16(heard.samples)[first:]
    robot = np.zeros(mic.shape[0], dtype=np.int16)
    for t0, chunk in room.played:
        samples = as_int16(convert(chunk, MODEL_FORMAT).samples)
        at = round((t0 - origin) * RATE)
        lo, hi = max(at, 0), min(at + samples.shape[0], robot.shape[0])
        if hi > lo:
            robot[lo:hi] = samples[lo - at : hi - at]
    return AudioChunk(np.stack([mic, robot], axis=1), STEREO, origin)


def write_session(path: str | Path, room: SimulatedRoom, origin: float) -> Path:
    """Write `session_audio` as a 16-bit stereo WAV; returns the path."""
    target = Path(path)
    if not target.parent.is_dir():
        raise AudioError(f"cannot write the session recording {target}: no folder {target.parent}")
    write_wav(target, session_audio(room, origin))
    return target


def reply_latency(session: AudioChunk, *, silence_dbfs: float = SILENCE_DBFS,
                  robot_dbfs: float | None = None) -> float | None:
    """Seconds from the user's last word to the robot's first sound, read off a session
    recording alone: the first sample of channel 2 louder than `robot_dbfs` (default
    `silence_dbfs`), minus the last sample of channel 1 louder than `silence_dbfs` before it.
    None when the robot made no sound (or nobody spoke). ``robot_dbfs=-100`` takes any
    non-zero sample: when the audio reached the speaker, before a synthesiser's own leading
    quiet (Piper's is ~50 ms), which is what the pipeline's ``first_audio`` marks."""
    if session.format.channels != 2:
        raise AudioError(f"a session recording has 2 channels (microphone, robot), this one has "
                         f"{session.format.channels}")
    samples = as_int16(session.samples).astype(np.float32) / 32768.0
    level = 10 ** (silence_dbfs / 20)
    robot = np.flatnonzero(np.abs(samples[:, 1]) > 10 ** ((silence_dbfs if robot_dbfs is None else robot_dbfs) / 20))
    if robot.size == 0:
        return None
    voiced = np.flatnonzero(np.abs(samples[: robot[0], 0]) > level)
    if voiced.size == 0:
        return None
    return float(robot[0] - voiced[-1]) / session.format.rate
