"""Settings of the voice pipeline (frozen; built once at the edge and passed down)."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import PurePath

from robovoice.audio.vad import EndpointerConfig
from robovoice.audio.wake import WakeDeciderConfig
from robovoice.config import VoiceConfig as VoiceSettings
from robovoice.errors import ConfigError


@dataclass(frozen=True, slots=True)
class TurnTakingConfig:
    """Times in seconds of microphone stream time.

    `command_timeout_s`: after a wake word with nothing more said, how long to wait for the
    command. `follow_up_s`: after the robot finished speaking, how long speech counts as an
    answer without the wake word (only when the robot asked a question, unless
    `follow_up_always`). `wake_slack_s`: a wake word this close to an utterance belongs to
    it. `stop_max_s`: only utterances up to this long are checked for a spoken stop (long
    enough for a stop said over other people's talk, which the VAD hears as speech too).
    `playback_tail_s`: after playback ends its echo still counts as playback this long.
    """

    command_timeout_s: float = 6.0
    follow_up_s: float = 5.0
    follow_up_always: bool = False
    wake_slack_s: float = 0.6
    stop_max_s: float = 4.0
    playback_tail_s: float = 0.3

    def __post_init__(self) -> None:
        for name in ("command_timeout_s", "follow_up_s", "wake_slack_s", "stop_max_s", "playback_tail_s"):
            if getattr(self, name) < 0:
                raise ConfigError(f"voice {name} must be >= 0")


@dataclass(frozen=True, slots=True)
class EchoConfig:
    """Self-voice rejection (docs/voice.md): echo cancellation against the playback signal;
    a raised wake threshold while anything plays (`playback_wake_threshold`); a wake word
    heard while the playback itself scores at least `playback_match_score` is the robot's
    own; speech heard during playback must be louder than what is left of the echo
    (`near_end_margin_db` above the measured leak)."""

    enabled: bool = True
    partitions: int = 8
    step: float = 0.5
    near_end_margin_db: float = 6.0
    playback_wake_threshold: float = 0.7
    playback_match_score: float = 0.2

    def __post_init__(self) -> None:
        if self.partitions < 1 or not 0 < self.step <= 1.5:
            raise ConfigError("echo partitions must be >= 1 and step in (0, 1.5]")
        if not 0.0 < self.playback_wake_threshold <= 1.0:
            raise ConfigError("playback_wake_threshold must be in (0, 1]")


@dataclass(frozen=True, slots=True)
class SpeechConfig:
    """Spoken output. `progress_interval_s`: at most one progress line per this many
    (wall-clock) seconds of a long action; `long_tools`: tools acknowledged at once when
    called (they take long); `stop_reply`: said after a spoken stop."""

    progress_interval_s: float = 8.0
    long_tools: tuple[str, ...] = ("navigate_to", "return_to_dock")
    stop_reply: str = "Stopped."
    queue_sentences: int = 8


@dataclass(frozen=True, slots=True)
class VoiceConfig:
    wake_model: str = "hey_jarvis"
    wake_phrase: str = "hey jarvis"
    wake: WakeDeciderConfig = field(default_factory=WakeDeciderConfig)
    endpointer: EndpointerConfig = field(default_factory=EndpointerConfig)
    turns: TurnTakingConfig = field(default_factory=TurnTakingConfig)
    echo: EchoConfig = field(default_factory=EchoConfig)
    speech: SpeechConfig = field(default_factory=SpeechConfig)
    vocabulary: tuple[str, ...] = ()  # extra speech-to-text hints (`robovoice.voice.vocabulary`)
    stop_tool: str = "stop_robot"
    motion_tools: tuple[str, ...] = ("navigate_to", "return_to_dock")
    stop_timeout_s: float = 5.0


def from_settings(settings: VoiceSettings) -> VoiceConfig:
    """The pipeline's config from the ``[voice]`` section of robovoice.toml."""
    phrase = settings.wake_phrase
    if phrase is None:  # the model's name as words: "hey_jarvis", ".../okay_robot_v0.2.onnx"
        phrase = re.sub(r"_v[\d.]+$", "", PurePath(settings.wake_model).stem).replace("_", " ")
    return VoiceConfig(
        wake_model=settings.wake_model,
        wake_phrase=phrase,
        wake=WakeDeciderConfig(threshold=settings.wake_threshold),
        endpointer=EndpointerConfig(end_silence_s=settings.end_of_turn_silence_ms / 1000.0,
                                    max_utterance_s=settings.max_utterance_s),
        turns=TurnTakingConfig(follow_up_s=settings.follow_up_s),
        vocabulary=tuple(settings.vocabulary),
    )
