"""The cut-off counter behind the shorter end-of-turn silence's figures (voice/speculate_eval.py),
on made-up VAD probabilities and a fake transcriber."""

from __future__ import annotations

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, silence
from robovoice.audio.stt import Transcript
from robovoice.voice.speculate_eval import VAD_FRAME, run_rule


class Words:
    def __init__(self, text: str) -> None:
        self.text = text
        self.calls = 0

    def transcribe(self, audio: AudioChunk, hint: str = "") -> Transcript:
        self.calls += 1
        return Transcript(self.text, audio.duration_s)


def probs(*spans: tuple[float, float]) -> tuple[AudioChunk, np.ndarray]:
    """(seconds, probability) spans as 32 ms frames, and silent audio of the same length."""
    values = np.concatenate([np.full(round(s * MODEL_FORMAT.rate / VAD_FRAME), p) for s, p in spans])
    return silence(MODEL_FORMAT, len(values) * VAD_FRAME / MODEL_FORMAT.rate), values


# "go to the kitchen" [0.4 s pause] "please" [silence]
SPEECH = ((0.3, 0.0), (1.0, 0.9), (0.4, 0.0), (0.5, 0.9), (1.0, 0.0))


def test_a_pause_longer_than_the_short_silence_after_complete_words_is_a_cut_off() -> None:
    audio, p = probs(*SPEECH)
    full = run_rule(audio, p, None, "", None, 0.5)
    early = run_rule(audio, p, Words("Hey Jarvis, go to the kitchen"), "", 0.3, 0.5)
    assert full.cut_offs == 0 and len(full.utterances) == 1
    assert early.cut_offs == 1 and early.utterances[0][3]  # ended early at the pause, then more speech
    assert early.pauses[0][1] == "go to the kitchen" and early.pauses[0][3]


def test_unfinished_words_keep_the_full_silence_and_a_finished_turn_ends_sooner() -> None:
    audio, p = probs(*SPEECH)
    early = run_rule(audio, p, Words("go to the"), "", 0.3, 0.5)
    assert early.cut_offs == 0 and not any(u[3] for u in early.utterances)
    audio, p = probs((0.3, 0.0), (1.0, 0.9), (1.0, 0.0))
    full = run_rule(audio, p, None, "", None, 0.5)
    early = run_rule(audio, p, Words("go to the kitchen"), "", 0.3, 0.5)
    [(_, end_full, decided_full, _)] = full.utterances
    [(_, end_early, decided_early, was_early)] = early.utterances
    assert was_early and end_early == end_full
    assert 0.15 <= decided_full - decided_early <= 0.25
