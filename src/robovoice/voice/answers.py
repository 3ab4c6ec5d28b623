"""What the pipeline answered: the last `KEEP_RESULTS` turns' `TurnResult`s (a spoken stop
counts as its stop tool's call), and, with an `output_dir`, each turn's spoken answer as
``turn-NN.wav``.

The results are bounded because the assistant runs for weeks in one process: only the most
recent turns are kept (enough for an evaluation or a test, which look at a handful), the
older ones are dropped. The audit log, not this list, is the record of every call.
"""

from __future__ import annotations

from pathlib import Path

from robovoice.assistant.loop import TurnResult
from robovoice.audio.wav import write_wav
from robovoice.voice.speech import SpeechOutput

#: How many of the latest turns' results are kept.
KEEP_RESULTS = 256


class AnswerRecorder:
    """See the module docstring. `keep`: how many of the latest results are kept (>= 1)."""

    def __init__(self, speech: SpeechOutput, output_dir: Path | None = None, *, keep: int = KEEP_RESULTS) -> None:
        if keep < 1:
            raise ValueError(f"AnswerRecorder keep must be at least 1 (the latest turn), got {keep!r}")
        self.speech = speech
        self.output_dir = output_dir
        self.keep = keep
        self.results: list[TurnResult] = []

    def add(self, result: TurnResult) -> None:
        self.results.append(result)
        if len(self.results) > self.keep:
            del self.results[: len(self.results) - self.keep]  # the oldest go; the list stays a list

    def save(self, turn: int) -> Path | None:
        """Write what was spoken for `turn` (and forget it); the file, if one was written."""
        audio = self.speech.take_recording(turn)
        if audio is None or self.output_dir is None:
            return None
        self.output_dir.mkdir(parents=True, exist_ok=True)
        path = self.output_dir / f"turn-{turn:02d}.wav"
        write_wav(path, audio)
        return path
