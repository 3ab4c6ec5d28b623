"""What the pipeline answered: each turn's `TurnResult` (a spoken stop counts as its stop
tool's call), and, with an `output_dir`, each turn's spoken answer as ``turn-NN.wav``."""

from __future__ import annotations

from pathlib import Path

from robovoice.assistant.loop import TurnResult
from robovoice.audio.wav import write_wav
from robovoice.voice.speech import SpeechOutput


class AnswerRecorder:
    """See the module docstring."""

    def __init__(self, speech: SpeechOutput, output_dir: Path | None = None) -> None:
        self.speech = speech
        self.output_dir = output_dir
        self.results: list[TurnResult] = []

    def add(self, result: TurnResult) -> None:
        self.results.append(result)

    def save(self, turn: int) -> Path | None:
        """Write what was spoken for `turn` (and forget it); the file, if one was written."""
        audio = self.speech.take_recording(turn)
        if audio is None or self.output_dir is None:
            return None
        self.output_dir.mkdir(parents=True, exist_ok=True)
        path = self.output_dir / f"turn-{turn:02d}.wav"
        write_wav(path, audio)
        return path
