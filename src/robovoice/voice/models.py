"""The voice models the pipeline needs, and loading the real ones (in parallel, warmed up)."""

from __future__ import annotations

import logging
import time
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass

from robovoice.audio.stt import Transcriber
from robovoice.audio.tts import Synthesizer
from robovoice.audio.vad import VADModel
from robovoice.audio.wake import WakeWordDetector

log = logging.getLogger(__name__)


def fixed_phrases() -> tuple[str, ...]:
    """What the robot says in the same words every time, by default (a config may change the
    stop replies; those are then synthesised at first use)."""
    from robovoice.config import VoiceConfig
    from robovoice.llm.failover import FALLBACK_MESSAGE
    from robovoice.voice.confidence import DIDNT_CATCH, TOO_NOISY

    voice = VoiceConfig()
    return (voice.stop_reply, voice.stop_failed_reply, voice.one_moment, DIDNT_CATCH, TOO_NOISY,
            FALLBACK_MESSAGE)


@dataclass(frozen=True, slots=True)
class VoiceModels:
    """`stt` may be None when the backend takes audio and no local stop check is wanted."""

    wake: WakeWordDetector
    vad: VADModel
    stt: Transcriber | None
    tts: Synthesizer
    playback_wake: WakeWordDetector | None = None  # a second instance, scoring the playback


def load_voice_models(
    *, wake_model: str = "hey_jarvis", stt: str = "whisper", stt_threads: int | None = None,
    tts_threads: int | None = None, wake_phases: int = 8,
) -> VoiceModels:
    """Load the shipped models: openWakeWord (twice: the microphone's and the playback's
    detector), Silero VAD, Whisper tiny.en (or Moonshine with ``stt="moonshine"``, none
    with ``stt="none"``) and Piper, four at a time."""
    from robovoice.audio.stt import MoonshineTranscriber, WhisperTranscriber
    from robovoice.audio.tts import PiperSynthesizer
    from robovoice.audio.tts_cache import CachedSynthesizer
    from robovoice.audio.vad import SileroVAD
    from robovoice.audio.wake import OpenWakeWordDetector

    started = time.perf_counter()
    with ThreadPoolExecutor(max_workers=4, thread_name_prefix="voice-load") as pool:
        wake = pool.submit(OpenWakeWordDetector, wake_model, phases=wake_phases)
        playback_wake = pool.submit(OpenWakeWordDetector, wake_model, phases=wake_phases)
        vad = pool.submit(SileroVAD)
        tts = pool.submit(PiperSynthesizer, intra_op_threads=tts_threads)
        transcriber: Future[Transcriber] | None = None
        if stt == "moonshine":
            transcriber = pool.submit(lambda: MoonshineTranscriber(threads=stt_threads))
        elif stt == "whisper":
            transcriber = pool.submit(lambda: WhisperTranscriber())
        speech = CachedSynthesizer(tts.result())
        # the phrases said again and again, synthesised now so that their first use is immediate
        speech.warm(fixed_phrases())
        models = VoiceModels(
            wake=wake.result(),
            vad=vad.result(),
            stt=transcriber.result() if transcriber is not None else None,
            tts=speech,
            playback_wake=playback_wake.result(),
        )
    log.info("voice models loaded in %.1f s", time.perf_counter() - started)
    return models
