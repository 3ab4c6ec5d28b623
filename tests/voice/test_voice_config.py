"""The pipeline's settings come from the [voice] section of robovoice.toml, and only from there."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from robovoice.config import VoiceConfig, load_config
from robovoice.errors import ConfigError
from robovoice.voice.config import EchoConfig, PipelineConfig, SpeechConfig, TurnTakingConfig


def _voice(tmp_path: Path, text: str) -> VoiceConfig:
    path = tmp_path / "robovoice.toml"
    path.write_text(text)
    return load_config(path).voice


def test_defaults_whisper_and_the_jarvis_phrase(tmp_path: Path) -> None:
    settings = _voice(tmp_path, "")
    config = PipelineConfig.from_config(settings)
    assert settings.stt == "whisper"
    assert config.wake_phrase == "hey jarvis" and config.vocabulary == ()


def test_one_set_of_defaults_whichever_way_the_config_is_built(tmp_path: Path) -> None:
    # the follow-up window was 6 s through the file and 5 s when built directly: one source now
    from_file = PipelineConfig.from_config(_voice(tmp_path, "[voice]\n"))
    assert from_file == PipelineConfig.from_config() == PipelineConfig.from_config(VoiceConfig())
    assert from_file.turns.follow_up_s == VoiceConfig().follow_up_s == 6.0


@pytest.mark.parametrize("runtime", [TurnTakingConfig, EchoConfig, SpeechConfig, PipelineConfig])
def test_the_runtime_settings_keep_no_defaults_of_their_own(runtime: type) -> None:
    fields = dataclasses.fields(runtime)
    assert all(f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING for f in fields)


@pytest.mark.parametrize(("model", "phrase"), [
    ("hey_mycroft", "hey mycroft"),
    ("/opt/models/okay_robot_v0.2.onnx", "okay robot"),
])
def test_the_wake_phrase_follows_the_model(tmp_path: Path, model: str, phrase: str) -> None:
    voice = _voice(tmp_path, f'[voice]\nwake_model = "{model}"\n')
    assert PipelineConfig.from_config(voice).wake_phrase == phrase


def test_phrase_vocabulary_and_engine_from_the_file(tmp_path: Path) -> None:
    settings = _voice(tmp_path, '[voice]\nwake_phrase = "hello robot"\nstt = "moonshine"\n'
                                'vocabulary = ["Grandma Ruth", "garden shed"]\n'
                                'follow_up_s = 4.5\nprogress_interval_s = 3\necho_cancellation = false\n')
    config = PipelineConfig.from_config(settings)
    assert settings.stt == "moonshine"
    assert config.wake_phrase == "hello robot"
    assert config.vocabulary == ("Grandma Ruth", "garden shed")
    assert config.turns.follow_up_s == 4.5 and config.speech.progress_interval_s == 3.0
    assert config.echo.enabled is False


def test_an_unknown_engine_names_the_file_and_the_field(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match=r"robovoice.toml: voice.stt"):
        _voice(tmp_path, '[voice]\nstt = "kaldi"\n')


def test_bad_values_are_refused_with_the_field(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match=r"voice.echo_partitions"):
        _voice(tmp_path, "[voice]\necho_partitions = 0\n")
