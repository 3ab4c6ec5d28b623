"""`AnswerRecorder` keeps only the latest turns' results: a process that runs for weeks must
not grow one `TurnResult` per turn forever."""

from __future__ import annotations

from collections.abc import AsyncIterator

import pytest

from robovoice.assistant.loop import TurnResult
from robovoice.assistant.metrics import TurnMetrics
from robovoice.audio.fakes import ToneSynthesizer
from robovoice.audio.wav import MemorySink
from robovoice.voice.answers import KEEP_RESULTS, AnswerRecorder
from robovoice.voice.inference import ModelExecutor
from robovoice.voice.speech import SpeechOutput


@pytest.fixture
async def speech() -> AsyncIterator[SpeechOutput]:
    executor = ModelExecutor("answers-test")
    yield SpeechOutput(ToneSynthesizer(), MemorySink(), executor, queue_size=4)
    await executor.aclose()


def _result(i: int) -> TurnResult:
    return TurnResult(f"reply {i}", (), (), TurnMetrics(start=float(i)))


async def test_results_keep_only_the_latest_turns(speech: SpeechOutput) -> None:
    recorder = AnswerRecorder(speech, keep=5)
    for i in range(12):
        recorder.add(_result(i))
    assert [r.reply for r in recorder.results] == [f"reply {i}" for i in range(7, 12)]
    assert isinstance(recorder.results, list)


async def test_the_default_bound_holds_over_many_turns(speech: SpeechOutput) -> None:
    recorder = AnswerRecorder(speech)
    for i in range(KEEP_RESULTS * 4 + 3):
        recorder.add(_result(i))
    assert len(recorder.results) == KEEP_RESULTS
    assert recorder.results[-1].reply == f"reply {KEEP_RESULTS * 4 + 2}"
    assert recorder.results[0].reply == f"reply {KEEP_RESULTS * 3 + 3}"


async def test_a_bound_below_one_is_refused_with_the_value(speech: SpeechOutput) -> None:
    with pytest.raises(ValueError, match=r"keep must be at least 1.*got 0"):
        AnswerRecorder(speech, keep=0)
