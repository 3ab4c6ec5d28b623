"""The voice pipeline's runtime settings (frozen), taken from the ``[voice]`` config.

`robovoice.config.VoiceConfig` (pydantic, the ``[voice]`` section of robovoice.toml) is the one
place defaults and limits live; the dataclasses here keep none of their own: each is built by
its ``from_config``, so a value set in the file and a value left to its default reach the
pipeline the same way.

    config = PipelineConfig.from_config(VoiceConfig(follow_up_s=4.0))

Which tools stop the robot, move it or tell its pose is not configuration: it comes from the
robot's manifests (`robovoice.voice.roles`).
"""

from __future__ import annotations

from dataclasses import dataclass

from robovoice.audio.vad import EndpointerConfig
from robovoice.audio.wake import WakeDeciderConfig
from robovoice.config import VoiceConfig


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

    command_timeout_s: float
    follow_up_s: float
    follow_up_always: bool
    wake_slack_s: float
    stop_max_s: float
    playback_tail_s: float

    @classmethod
    def from_config(cls, voice: VoiceConfig) -> TurnTakingConfig:
        return cls(voice.command_timeout_s, voice.follow_up_s, voice.follow_up_always, voice.wake_slack_s,
                   voice.stop_max_s, voice.playback_tail_s)


@dataclass(frozen=True, slots=True)
class EchoConfig:
    """Self-voice rejection (docs/voice.md): echo cancellation against the playback signal;
    a raised wake threshold while anything plays (`playback_wake_threshold`); a wake word
    heard while the playback itself scores at least `playback_match_score` is the robot's
    own; speech heard during playback must be louder than what is left of the echo
    (`near_end_margin_db` above the measured leak)."""

    enabled: bool
    partitions: int
    step: float
    near_end_margin_db: float
    playback_wake_threshold: float
    playback_match_score: float

    @classmethod
    def from_config(cls, voice: VoiceConfig) -> EchoConfig:
        return cls(voice.echo_cancellation, voice.echo_partitions, voice.echo_step, voice.near_end_margin_db,
                   voice.playback_wake_threshold, voice.playback_match_score)


@dataclass(frozen=True, slots=True)
class SpeechConfig:
    """Spoken output. `progress_interval_s`: at most one progress line per this many
    (wall-clock) seconds of a long action; `stop_reply` / `stop_failed_reply`: said after a
    spoken stop (unless the stop tool's manifest declares its own phrases); `queue_sentences`:
    how many sentences may wait for speech; `one_moment`: said once in a turn when nothing
    else would be heard `one_moment_after_s` after the end of the user's turn ("" = never)."""

    progress_interval_s: float
    stop_reply: str
    stop_failed_reply: str
    queue_sentences: int
    one_moment: str
    one_moment_after_s: float

    @classmethod
    def from_config(cls, voice: VoiceConfig) -> SpeechConfig:
        return cls(voice.progress_interval_s, voice.stop_reply, voice.stop_failed_reply, voice.speech_queue,
                   voice.one_moment.strip(), voice.one_moment_after_s)


@dataclass(frozen=True, slots=True)
class SpeculationConfig:
    """Using the end-of-turn silence (`voice.speculate`, docs/voice.md): `early_end`: after a
    complete request, end the turn after `early_silence_s` of silence instead of the full one;
    `prefill`: prefill the model on the speculative transcript; `decode`: decode its tool
    call too (only with `prefill`)."""

    early_end: bool
    early_silence_s: float
    prefill: bool
    decode: bool

    @classmethod
    def from_config(cls, voice: VoiceConfig) -> SpeculationConfig:
        return cls(voice.early_end, voice.early_end_silence_ms / 1000.0, voice.speculative_prefill,
                   voice.speculative_decode)


@dataclass(frozen=True, slots=True)
class ConfidenceCheck:
    """`min_avg_logprob`: a command transcript whose mean token log-probability is below it
    is turned away (`voice.confidence`); `confirm_below`: below it, a tool with a confirm
    question is asked about before it runs (`assistant.confirm`); `min_snr_db`: a command
    whose speech is less than this much louder than the noise around it is turned away
    (`voice.confidence.too_noisy`). None turns each off."""

    min_avg_logprob: float | None
    confirm_below: float | None = None
    min_snr_db: float | None = None

    @classmethod
    def from_config(cls, voice: VoiceConfig) -> ConfidenceCheck:
        return cls(voice.confidence_min_logprob if voice.confidence_check else None,
                   voice.confirm_below_logprob if voice.confirm_doubtful else None,
                   voice.confidence_min_snr_db if voice.confidence_check else None)


@dataclass(frozen=True, slots=True)
class PipelineConfig:
    """Everything `VoicePipeline` is tuned by. `wake_phrase`: what the wake word says (for
    stripping it from transcripts and for speech-to-text hints); `vocabulary`: extra words for
    speech-to-text; `stop_timeout_s`: how long a spoken stop waits for the stop tool;
    `speculation`: what the speculative transcript is used for; `confidence`: which command
    transcripts are too unsure to act on."""

    wake_phrase: str
    wake: WakeDeciderConfig
    endpointer: EndpointerConfig
    turns: TurnTakingConfig
    echo: EchoConfig
    speech: SpeechConfig
    vocabulary: tuple[str, ...]
    stop_timeout_s: float
    speculation: SpeculationConfig
    confidence: ConfidenceCheck

    @classmethod
    def from_config(cls, voice: VoiceConfig | None = None) -> PipelineConfig:
        """From the ``[voice]`` section (None: its defaults)."""
        voice = voice if voice is not None else VoiceConfig()
        return cls(
            wake_phrase=voice.spoken_wake_phrase,
            wake=WakeDeciderConfig(threshold=voice.wake_threshold,
                                   unsure_threshold=voice.wake_unsure_threshold or None),
            endpointer=EndpointerConfig(end_silence_s=voice.end_of_turn_silence_ms / 1000.0,
                                        max_utterance_s=voice.max_utterance_s),
            turns=TurnTakingConfig.from_config(voice),
            echo=EchoConfig.from_config(voice),
            speech=SpeechConfig.from_config(voice),
            vocabulary=tuple(voice.vocabulary),
            stop_timeout_s=voice.stop_timeout_s,
            speculation=SpeculationConfig.from_config(voice),
            confidence=ConfidenceCheck.from_config(voice),
        )
