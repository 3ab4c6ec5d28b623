"""The ``[voice]`` keys for using the end-of-turn silence and for the transcript check: read
from a config file, they change what the speculator does (the transcript check's effect is
in test_confidence.py); a bad value is refused with the key and the fix."""

from __future__ import annotations

from pathlib import Path

import pytest

from robovoice.config import load_config
from robovoice.errors import ConfigError
from robovoice.voice.config import PipelineConfig

from .test_speculation import follow


def pipeline_config(tmp_path: Path, keys: str) -> PipelineConfig:
    path = tmp_path / "robovoice.toml"
    path.write_text(f"[voice]\n{keys}\n", encoding="utf-8")
    return PipelineConfig.from_config(load_config(path).voice)


def test_the_defaults_are_the_measured_ones() -> None:
    config = PipelineConfig.from_config()
    assert (config.speculation.early_end, config.speculation.early_silence_s) == (True, 0.3)
    assert config.speculation.prefill and config.speculation.decode
    assert config.confidence.min_avg_logprob == -0.6


async def test_early_end_silence_ms_sets_the_shorter_silence(tmp_path: Path) -> None:
    config = pipeline_config(tmp_path, "early_end_silence_ms = 200")
    allowed, _, _ = await follow("Hey Jarvis, go to the kitchen.", config=config.speculation)
    assert allowed == [0.2]


async def test_early_end_false_keeps_the_full_silence_but_still_prefills(tmp_path: Path) -> None:
    config = pipeline_config(tmp_path, "early_end = false")
    allowed, _, prefills = await follow("Hey Jarvis, go to the kitchen.", config=config.speculation)
    assert allowed == [] and len(prefills) == 1


async def test_speculative_prefill_false_prefills_nothing(tmp_path: Path) -> None:
    config = pipeline_config(tmp_path, "speculative_prefill = false")
    allowed, assistant, prefills = await follow("Hey Jarvis, go to the kitchen.", config=config.speculation)
    assert allowed == [0.3] and assistant.asked == [] and prefills == []


async def test_speculative_decode_false_prefills_the_prompt_only(tmp_path: Path) -> None:
    config = pipeline_config(tmp_path, "speculative_decode = false")
    _, _, prefills = await follow("Hey Jarvis, go to the kitchen.", config=config.speculation)
    [(_, _, decode)] = prefills
    assert decode is False


@pytest.mark.parametrize(("keys", "named", "fix"), [
    ("early_end_silence_ms = 20", "voice.early_end_silence_ms", "give milliseconds from 50 to 5000"),
    ("early_end_silence_ms = 600", "early_end_silence_ms = 600 is not shorter than end_of_turn_silence_ms = 500",
     "or set early_end = false"),
    ("end_of_turn_silence_ms = 250", "early_end_silence_ms = 300 is not shorter", "give a shorter one"),
    ("confidence_min_logprob = 0.5", "voice.confidence_min_logprob", "from -10 up to (not including) 0"),
    ("confidence_min_logprob = -40", "voice.confidence_min_logprob", "or set confidence_check = false"),
    ("speculative_prefill = \"maybe\"", "voice.speculative_prefill", "valid boolean"),
])
def test_a_bad_value_names_the_key_and_the_fix(tmp_path: Path, keys: str, named: str, fix: str) -> None:
    with pytest.raises(ConfigError) as caught:
        pipeline_config(tmp_path, keys)
    message = str(caught.value)
    assert "robovoice.toml" in message and named in message and fix in message, message


def test_a_long_early_silence_is_fine_when_the_early_end_is_off(tmp_path: Path) -> None:
    config = pipeline_config(tmp_path, "early_end = false\nearly_end_silence_ms = 800")
    assert not config.speculation.early_end
