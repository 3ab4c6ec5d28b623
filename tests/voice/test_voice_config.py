"""The pipeline's settings from the [voice] section of robovoice.toml."""

from __future__ import annotations

from pathlib import Path

import pytest

from robovoice.config import load_config
from robovoice.errors import ConfigError
from robovoice.voice.config import from_settings


def _voice(tmp_path: Path, text: str):  # type: ignore[no-untyped-def]
    path = tmp_path / "robovoice.toml"
    path.write_text(text)
    return load_config(path).voice


def test_defaults_whisper_and_the_jarvis_phrase(tmp_path: Path) -> None:
    settings = _voice(tmp_path, "")
    config = from_settings(settings)
    assert settings.stt == "whisper"
    assert config.wake_phrase == "hey jarvis" and config.vocabulary == ()


@pytest.mark.parametrize(("model", "phrase"), [
    ("hey_mycroft", "hey mycroft"),
    ("/opt/models/okay_robot_v0.2.onnx", "okay robot"),
])
def test_the_wake_phrase_follows_the_model(tmp_path: Path, model: str, phrase: str) -> None:
    assert from_settings(_voice(tmp_path, f'[voice]\nwake_model = "{model}"\n')).wake_phrase == phrase


def test_phrase_vocabulary_and_engine_from_the_file(tmp_path: Path) -> None:
    settings = _voice(tmp_path, '[voice]\nwake_phrase = "hello robot"\nstt = "moonshine"\n'
                                'vocabulary = ["Grandma Ruth", "garden shed"]\n')
    config = from_settings(settings)
    assert settings.stt == "moonshine"
    assert config.wake_phrase == "hello robot"
    assert config.vocabulary == ("Grandma Ruth", "garden shed")


def test_an_unknown_engine_names_the_file_and_the_field(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match=r"robovoice.toml: voice.stt"):
        _voice(tmp_path, '[voice]\nstt = "kaldi"\n')
