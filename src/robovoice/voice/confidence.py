"""Whether a command's transcript is sure enough to act on (issue 11, docs/judgement.md
"Transcript confidence").

Speech-to-text always returns *some* words: in heavy noise Whisper, helped by the
vocabulary hint, hears "open the kitchen" or "when is Ben?" in a blur of voices, and the
model would act on it. A transcript the speech-to-text model itself was unsure of is turned
away with "Sorry, I didn't catch that." instead of becoming a model turn that could move
the robot. A spoken stop never comes here: it is acted on before.

The measure is Whisper's mean token log-probability of the transcript (`avg_logprob`,
the lowest over segments), chosen over the mean probability of the command's words on
the dev audio sets (docs/judgement.md): it separated the dev commands buried in noise from
the clear ones without turning a clear one away; the word probabilities turned away short
clear commands ("Call Anna." scored 0.06). The threshold is ``[voice] confidence_min_logprob``
(-0.6: between the dev set's least sure clear command, -0.54, and its surest command buried
in noise, -0.69); ``confidence_check = false`` turns the check off. A transcript without
scores (Moonshine) is never turned away.

Between that threshold and ``[voice] confirm_below_logprob`` (-0.4) a transcript is in doubt
(`doubtful`): acted on, but a tool that declares a confirm question ("Shall I call Anna?") is
asked about first (assistant/confirm.py).

Whisper is also sure of words it could hardly hear: on the dev clips drowned in noise (-5 to
-1 dB) it wrote three commands word for word at -0.2 to -0.33. A transcript is not turned away
for that alone, but a command whose speech is under ``[voice] confidence_min_snr_db`` (6 dB)
above the noise around it is (`too_noisy`, measured by `audio.level`): "Sorry, it is too noisy
for me to be sure what you said." A spoken stop is acted on before either check.
"""

from __future__ import annotations

import logging
import re

from robovoice.audio.format import AudioChunk
from robovoice.audio.level import speech_to_noise_db
from robovoice.audio.stt import Confidence, Transcript, WordScore
from robovoice.voice.config import ConfidenceCheck

log = logging.getLogger(__name__)

DIDNT_CATCH = "Sorry, I didn't catch that."
TOO_NOISY = "Sorry, it is too noisy for me to be sure what you said."
_NOISY = "noisy"  # how a `too_noisy` reason begins

_WORD = re.compile(r"[A-Za-z0-9]+(?:'[A-Za-z]+)?")


def command_words(confidence: Confidence, text: str) -> list[WordScore]:
    """The scored words of the command `text` (the transcript with the wake phrase removed):
    as many of the transcript's last words as `text` has words; punctuation is left out."""
    words = [w for w in confidence.words if _WORD.search(w.word)]
    wanted = len(_WORD.findall(text))
    return words[len(words) - wanted :] if 0 < wanted <= len(words) else words


def mean_word_probability(confidence: Confidence, text: str) -> float | None:
    """The mean probability of the command's words; None when there are no scored words."""
    words = command_words(confidence, text)
    return sum(w.probability for w in words) / len(words) if words else None


# one word (or two or three) six times in a row or more: the decoder looping on noise, not speech ("stop, stop, wait,
# wait, wait, …" 22 times for "Hey Jarvis, Doctor Weber is a very kind man, you know." in pink
# noise, audio test v120, with the hint's stop words: the robot, standing still, was stopped)
_LOOP = re.compile(r"\b(\w+(?:\W+\w+){0,2})\b(?:\W+\1\b){5,}", re.IGNORECASE)  # "hang up, …" 14 times (v121)


def unsure_reason(transcript: Transcript, text: str, check: ConfidenceCheck) -> str | None:
    """Why the command `text` (from `transcript`, wake phrase removed) is too unsure to act
    on, or None to act. The scores are logged either way (`robovoice -v`). A decoder loop
    (`_LOOP`) is unsure whatever its scores, while the check is on."""
    if check.min_avg_logprob is not None and _LOOP.search(text):
        return "unsure: one word over and over (the speech-to-text model looping)"
    if transcript.confidence is None:
        return None
    scores = transcript.confidence
    words = mean_word_probability(scores, text)
    log.info("transcript confidence: avg_logprob %.3f, mean word probability %s, no speech %.2f: %r",
             scores.avg_logprob, "-" if words is None else f"{words:.3f}", scores.no_speech_prob, text)
    if check.min_avg_logprob is not None and scores.avg_logprob < check.min_avg_logprob:
        return f"unsure: mean log-probability {scores.avg_logprob:.2f} < {check.min_avg_logprob:.2f}"
    return None


def doubtful(transcript: Transcript, check: ConfidenceCheck) -> bool:
    """Sure enough to act on, but not to run a call that cannot be taken back unasked: the
    assistant asks "Shall I call Anna?" first (`assistant.confirm`). A transcript without
    scores (Moonshine) is never in doubt."""
    scores = transcript.confidence
    return check.confirm_below is not None and scores is not None and scores.avg_logprob < check.confirm_below


def too_noisy(audio: AudioChunk, check: ConfidenceCheck) -> str | None:
    """Why the utterance `audio` (a VAD cut, its pre- and post-roll included) is too noisy to act
    on, or None to act: its speech is less than `check.min_snr_db` above the noise around it."""
    if check.min_snr_db is None:
        return None
    snr = speech_to_noise_db(audio)
    log.info("speech to noise: %s dB", "-" if snr is None else f"{snr:.1f}")
    if snr is not None and snr < check.min_snr_db:
        return f"{_NOISY}: speech {snr:.1f} dB over the noise < {check.min_snr_db:.1f}"
    return None


def turned_away_with(reason: str) -> str:
    """What the robot says when a command is turned away for `reason`."""
    return TOO_NOISY if reason.startswith(_NOISY) else DIDNT_CATCH
