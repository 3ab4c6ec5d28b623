#!/usr/bin/env python3
"""Synthesise test audio for the voice pipeline, offline, from a list of clip specs.

Voices: Piper (the packaged en_US "joe" voice, optionally slower/faster) and espeak-ng
(Debian package ``espeak-ng``; several accents, variants and speeds). Each clip is
16 kHz mono int16: ``lead_s`` of silence, the speech, ``tail_s`` of silence, optionally
mixed with noise (white, pink, or babble made from other synthetic speech) at a given SNR,
where SNR compares the *active* speech level with the noise level.

Sets:
  tests      the small set committed under tests/data/audio (default)
  eval       40 clips for the end-to-end evaluation (wake / no wake, clean and noisy)
  spec FILE  a JSON list of {"id", "text", "voice", "wake", "snr_db"?, "noise"?} objects

Every set writes ``<out>/<id>.wav`` and ``<out>/clips.json`` (the specs plus measured
duration and speech start/end). ``--negative-minutes N --negative-out FILE`` writes one
long clip of varied speech and noise *without* the wake phrase (wake-word false accepts).

Examples:
  python scripts/make_audio_fixtures.py                      # tests/data/audio
  python scripts/make_audio_fixtures.py --set eval --out out/eval-audio
  python scripts/make_audio_fixtures.py --negative-minutes 10 --negative-out out/negative.wav
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from robovoice.audio.format import MODEL_FORMAT, AudioChunk, as_float32, convert, float32_to_int16
from robovoice.audio.wav import read_wav, write_wav

RATE = MODEL_FORMAT.rate
ROOT = Path(__file__).resolve().parent.parent
DEFAULT_OUT = ROOT / "tests" / "data" / "audio"


@dataclass(frozen=True)
class ClipSpec:
    """One clip. `voice`: ``piper`` / ``piper:<length_scale>`` or ``espeak:<voice>[:<words per
    minute>]`` (e.g. ``espeak:en-gb-scotland:150``, ``espeak:en-us+f3``). `noise`: white,
    pink or babble (needs `snr_db`)."""

    id: str
    text: str
    voice: str
    wake: bool
    snr_db: float | None = None
    noise: str | None = None
    lead_s: float = 0.6
    tail_s: float = 1.2


# --- the sets ------------------------------------------------------------------------------------

TEST_SET: list[ClipSpec] = [
    ClipSpec("wake_piper_projector", "Hey Jarvis, turn on the projector.", "piper", True),
    ClipSpec("wake_piper_kitchen_pink20", "Hey Jarvis, go to the kitchen.", "piper", True, 20, "pink"),
    ClipSpec("wake_piper_call_babble10", "Hey Jarvis, call Anna.", "piper:1.1", True, 10, "babble"),
    ClipSpec("wake_piper_battery_white10", "Hey Jarvis, how full is your battery?", "piper", True, 10,
             "white"),
    ClipSpec("wake_espeak_dock", "Hey Jarvis, go back to your charging dock.", "espeak:en-us:150", True),
    ClipSpec("wakeonly_piper", "Hey Jarvis.", "piper", True),
    ClipSpec("cmd_piper_kitchen", "Robot, go to the kitchen.", "piper", False),
    ClipSpec("tv_espeak_weather", "And now the weather. Tomorrow will be cloudy, with showers in the north.",
             "espeak:en-gb:165", False),
    ClipSpec("tv_piper_news_babble10", "The minister said the new bridge will open next spring.",
             "piper:0.95", False, 10, "babble"),
]  # fmt: skip

_WAKE_COMMANDS = [
    "turn on the projector", "switch the projector off", "go to the kitchen", "drive to the bedroom",
    "call Anna", "start a video call with Dr. Weber", "how much battery do you have left",
    "where are you right now", "go back to your charging dock", "stop", "what can you see",
    "take me to the front door",
]  # fmt: skip
_NO_WAKE = [
    "Robot, go to the kitchen.", "Turn on the projector, please.", "Call Ben for me.",
    "And now the weather for the weekend.", "I think the game starts at eight tonight.",
    "Could you pass me the salt?", "The bus was late again this morning.", "Hey Travis, long time no see!",
]  # fmt: skip
_VOICES = ["piper", "piper:1.15", "espeak:en-us:150", "espeak:en-gb:165", "espeak:en-us+f3:140",
           "espeak:en-gb-scotland:155", "piper:0.9", "espeak:en-029:150"]  # fmt: skip
_NOISES: list[tuple[float | None, str | None]] = [
    (None, None),
    (20, "pink"),
    (10, "babble"),
    (20, "white"),
    (10, "pink"),
]


def eval_set() -> list[ClipSpec]:
    """24 wake-word commands and 16 clips without the wake phrase, voices and noise rotated."""
    clips: list[ClipSpec] = []
    for i, cmd in enumerate(_WAKE_COMMANDS * 2):
        snr, noise = _NOISES[i % len(_NOISES)]
        voice = _VOICES[i % len(_VOICES)]
        text = f"Hey Jarvis, {cmd}{'?' if cmd.startswith(('how', 'where', 'what')) else '.'}"
        clips.append(ClipSpec(f"wake-{i + 1:02d}", text, voice, True, snr, noise))
    for i, text in enumerate(_NO_WAKE * 2):
        snr, noise = _NOISES[(i + 2) % len(_NOISES)]
        clips.append(ClipSpec(f"nowake-{i + 1:02d}", text, _VOICES[(i + 3) % len(_VOICES)], False, snr, noise))
    return clips


#: Talk without the wake phrase, for false-accept measurement and babble noise.
NEGATIVE_TEXTS = [
    "Good evening, and welcome to the news at six.",
    "The government announced new measures to support small businesses today.",
    "Temperatures will reach twenty-five degrees in the south by Thursday.",
    "In sport, the home team won three to one after a difficult first half.",
    "Could you put the kettle on? I would love a cup of tea.",
    "Grandma, your doctor called about the appointment on Monday.",
    "We are out of milk again, I will get some tomorrow.",
    "The film starts at eight, so we should leave at half past seven.",
    "Have you seen my glasses? I left them on the table.",
    "Traffic on the motorway is heavy because of an accident near the bridge.",
    "This recipe needs two eggs, a cup of flour and a pinch of salt.",
    "The museum is open every day except Tuesday.",
    "Hey Travis, how was your holiday in Spain?",
    "Harvey said the garden looks lovely this year.",
    "Hey, is this the right bus for the station?",
    "The robot vacuum got stuck under the sofa again.",
    "Please remember to water the plants while I am away.",
    "Scientists have discovered a new species of frog in the rainforest.",
    "The interest rate will stay at four percent for now.",
    "Open the window, it is getting warm in here.",
    "Jars of honey are on sale at the market this weekend.",
    "I will call you back after dinner, okay?",
    "Here is a look at the stories making headlines this hour.",
    "The concert was cancelled because of the storm.",
    "Our next guest has written three books about gardening in small spaces.",
    "Add the onions and fry them gently until they are golden.",
    "The train to Manchester is delayed by about twenty minutes.",
    "Did you remember to lock the back door last night?",
    "Stocks fell sharply this morning after the announcement.",
    "My knee has been hurting since I went for that long walk.",
    "The children are coming to visit on Sunday afternoon.",
    "Turn left at the church and then take the second right.",
    "This episode was recorded in front of a live audience.",
    "Which one do you prefer, the blue one or the green one?",
    "The parcel will be delivered between ten and twelve.",
    "He scored twice in the last ten minutes of the match.",
    "Police are asking drivers to avoid the city centre tonight.",
    "I have no idea where I put the remote control.",
    "The library has a new reading group for older adults.",
    "Thank you for calling, please hold the line.",
    "Jarrod and Maggie are getting married in June.",
    "Hey, did you hear what happened at the council meeting?",
    "Travelling by ferry is much cheaper in the winter months.",
    "The soup needs a little more salt and some pepper.",
    "According to the report, unemployment fell again last month.",
    "Let us take a short break and we will be right back.",
    "My grandson showed me how to make video calls on the tablet.",
    "Apparently the heating engineer is coming on Wednesday.",
    "The election results will be announced after midnight.",
    "Could you read the letter to me? My eyes are tired today.",
    "The garden centre has a sale on roses this week.",
    "Jasmine tea is my favourite in the evening.",
    "Harvest festival starts on the first weekend of October.",
    "A jar of jam and a loaf of bread, please.",
    "The vet said the dog needs to lose a little weight.",
    "Remember, your appointment with the optician is at three.",
    "In other news, a rare bird was spotted on the coast.",
    "Dinner is ready, come and sit down while it is hot.",
]


# --- synthesis -----------------------------------------------------------------------------------


class Voices:
    """Synthesises text with Piper or espeak-ng, returning 16 kHz mono float32."""

    def __init__(self) -> None:
        self._piper: dict[float | None, object] = {}
        self._espeak = shutil.which("espeak-ng")
        self._babble: np.ndarray | None = None

    def babble_bed(self, seconds: float = 30.0) -> np.ndarray:
        """Six synthetic talkers at once, each reading the negative texts (made once)."""
        if self._babble is None:
            rng = np.random.default_rng(1234)
            n = int(seconds * RATE)
            bed = np.zeros(n)
            talkers = ["espeak:en-us:170", "espeak:en-gb+f3:160", "espeak:en-gb-scotland:175", "piper:1.0",
                       "espeak:en-029:150", "espeak:en-us+m3:180"]  # fmt: skip
            for t, voice in enumerate(talkers):
                stream: list[np.ndarray] = []
                length = 0
                for i in rng.permutation(len(NEGATIVE_TEXTS)):
                    s = self.speak(NEGATIVE_TEXTS[int(i)], voice)
                    stream.append(s / max(1e-6, np.sqrt(active_power(s))))
                    length += len(s)
                    if length >= n:
                        break
                talk = np.tile(np.concatenate(stream), 2)[:n]
                bed += np.roll(talk, int(rng.integers(n))) * (0.7 + 0.1 * (t % 3))
            self._babble = bed
        return self._babble

    def speak(self, text: str, voice: str) -> np.ndarray:
        kind, _, arg = voice.partition(":")
        if kind == "piper":
            return self._speak_piper(text, float(arg) if arg else None)
        if kind == "espeak":
            name, _, wpm = arg.partition(":")
            return self._speak_espeak(text, name or "en-us", int(wpm) if wpm else 160)
        raise SystemExit(f"unknown voice {voice!r}: use piper[:length_scale] or espeak:<voice>[:wpm]")

    def _speak_piper(self, text: str, length_scale: float | None) -> np.ndarray:
        from robovoice.audio.tts import PiperSynthesizer

        synth = self._piper.get(length_scale)
        if synth is None:
            synth = PiperSynthesizer(length_scale=length_scale, sentence_silence_s=0.0, volume=1.0)
            self._piper[length_scale] = synth
        assert isinstance(synth, PiperSynthesizer)
        return as_float32(convert(synth.synthesize(text), MODEL_FORMAT).samples)

    def _speak_espeak(self, text: str, voice: str, wpm: int) -> np.ndarray:
        if self._espeak is None:
            raise SystemExit("espeak-ng not found: apt-get install espeak-ng")
        with tempfile.TemporaryDirectory() as tmp:
            wav = Path(tmp) / "e.wav"
            subprocess.run([self._espeak, "-v", voice, "-s", str(wpm), "-w", str(wav), text], check=True)
            chunk = read_wav(wav)
        x = as_float32(convert(chunk, MODEL_FORMAT).samples)
        return x / max(1e-6, float(np.max(np.abs(x))))


# --- noise and mixing ----------------------------------------------------------------------------


def active_power(x: np.ndarray, frame: int = 320, floor_db: float = 30.0) -> float:
    """Mean power of the frames within `floor_db` of the loudest (speech without pauses)."""
    n = len(x) // frame
    if n == 0:
        return float(np.mean(x.astype(np.float64) ** 2))
    p = np.mean(x[: n * frame].astype(np.float64).reshape(n, frame) ** 2, axis=1)
    active = p[p >= p.max() * 10 ** (-floor_db / 10)]
    return float(np.mean(active))


def make_noise(kind: str, n: int, rng: np.random.Generator, voices: Voices | None = None) -> np.ndarray:
    if kind == "white":
        return rng.standard_normal(n)
    if kind == "pink":
        spec = np.fft.rfft(rng.standard_normal(n))
        f = np.arange(spec.shape[0], dtype=np.float64)
        f[0] = 1.0
        return np.fft.irfft(spec / np.sqrt(f), n)
    if kind == "babble":
        if voices is None:
            raise ValueError("babble noise needs voices")
        bed = voices.babble_bed()
        reps = -(-n // len(bed)) + 1
        start = int(rng.integers(0, len(bed)))
        return np.tile(bed, reps)[start : start + n]
    raise ValueError(f"unknown noise {kind!r}: white, pink or babble")


def mix(speech: np.ndarray, noise: np.ndarray, snr_db: float) -> np.ndarray:
    scale = np.sqrt(active_power(speech) / (10 ** (snr_db / 10)) / max(1e-20, float(np.mean(noise**2))))
    return speech + noise * scale


def render(spec: ClipSpec, voices: Voices) -> tuple[np.ndarray, float, float]:
    """The clip (float32 16 kHz) and where the speech starts and ends in it (s)."""
    rng = np.random.default_rng(int(hashlib.sha256(spec.id.encode()).hexdigest()[:8], 16))
    speech = voices.speak(spec.text, spec.voice)
    speech = speech / np.sqrt(active_power(speech)) * 10 ** (-20 / 20)  # -20 dBFS active level
    start, end = _speech_bounds(speech)
    lead = np.zeros(round(spec.lead_s * RATE))
    tail = np.zeros(round(spec.tail_s * RATE))
    clip = np.concatenate((lead, speech, tail))
    if spec.noise is not None:
        if spec.snr_db is None:
            raise SystemExit(f"{spec.id}: noise needs snr_db")
        clip = mix(clip, make_noise(spec.noise, len(clip), rng, voices), spec.snr_db)
    peak = float(np.max(np.abs(clip)))
    if peak > 0.95:
        clip *= 0.95 / peak
    return clip.astype(np.float32), spec.lead_s + start, spec.lead_s + end


def _speech_bounds(x: np.ndarray, frame: int = 160) -> tuple[float, float]:
    n = len(x) // frame
    p = np.mean(x[: n * frame].astype(np.float64).reshape(n, frame) ** 2, axis=1)
    loud = np.nonzero(p >= p.max() * 1e-4)[0]  # within 40 dB of the peak
    return float(loud[0] * frame / RATE), float((loud[-1] + 1) * frame / RATE)


def write_set(specs: Sequence[ClipSpec], out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    voices = Voices()
    index = []
    for spec in specs:
        clip, start, end = render(spec, voices)
        write_wav(out / f"{spec.id}.wav", AudioChunk(float32_to_int16(clip), MODEL_FORMAT))
        index.append(
            {**dataclasses.asdict(spec), "duration_s": round(len(clip) / RATE, 3),
             "speech_start_s": round(start, 3), "speech_end_s": round(end, 3)}
        )  # fmt: skip
        print(f"{spec.id}: {len(clip) / RATE:.2f} s, speech {start:.2f}-{end:.2f} s", file=sys.stderr)
    (out / "clips.json").write_text(json.dumps(index, indent=1) + "\n", encoding="utf-8")


def write_negative(minutes: float, path: Path, seed: int = 7) -> None:
    """Varied talk without the wake phrase: random texts, voices, levels and pauses, noise on
    about half of the sentences (pink/white/babble at 10-20 dB SNR). A JSON file beside the
    WAV lists every sentence with its time, voice and noise."""
    rng = np.random.default_rng(seed)
    voices = Voices()
    all_voices = [*_VOICES, "espeak:en-us+f2:170", "espeak:en-gb-x-rp:160", "espeak:en-us-nyc:175"]
    parts: list[np.ndarray] = []
    segments: list[dict[str, object]] = []
    total = 0
    target = int(minutes * 60 * RATE)
    while total < target:
        text = NEGATIVE_TEXTS[int(rng.integers(len(NEGATIVE_TEXTS)))]
        voice = all_voices[int(rng.integers(len(all_voices)))]
        s = voices.speak(text, voice)
        speech_s = len(s) / RATE
        s = s / np.sqrt(active_power(s)) * 10 ** (float(rng.uniform(-30, -15)) / 20)
        s = np.concatenate((s, np.zeros(int(rng.uniform(0.2, 1.5) * RATE))))
        noise: str | None = None
        snr: float | None = None
        if rng.random() < 0.5:
            noise = ["pink", "white", "babble"][int(rng.integers(3))]
            snr = round(float(rng.uniform(10, 20)), 1)
            s = mix(s, make_noise(noise, len(s), rng, voices if noise == "babble" else None), snr)
        segments.append(
            {"start_s": round(total / RATE, 2), "end_s": round(total / RATE + speech_s, 2), "text": text,
             "voice": voice, "noise": noise, "snr_db": snr}
        )  # fmt: skip
        parts.append(s)
        total += len(s)
        print(f"negative: {total / RATE / 60:.1f} / {minutes} min", file=sys.stderr, end="\r")
    clip = np.concatenate(parts)[:target]
    clip *= min(1.0, 0.95 / float(np.max(np.abs(clip))))
    path.parent.mkdir(parents=True, exist_ok=True)
    write_wav(path, AudioChunk(float32_to_int16(clip), MODEL_FORMAT))
    path.with_suffix(".json").write_text(json.dumps(segments, indent=0) + "\n", encoding="utf-8")
    print(f"\nwrote {path} ({len(clip) / RATE / 60:.1f} min)", file=sys.stderr)


def load_spec_file(path: Path) -> list[ClipSpec]:
    items = json.loads(path.read_text(encoding="utf-8"))
    fields = {f.name for f in dataclasses.fields(ClipSpec)}
    return [ClipSpec(**{k: v for k, v in item.items() if k in fields}) for item in items]


def main(argv: Iterable[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--set", default="tests", help="tests | eval | spec")
    parser.add_argument("--spec", type=Path, help="JSON list of clip specs (with --set spec)")
    parser.add_argument("--out", type=Path, help=f"output folder (default {DEFAULT_OUT} for tests)")
    parser.add_argument("--only", nargs="*", help="only these clip ids")
    parser.add_argument("--negative-minutes", type=float, default=0.0)
    parser.add_argument("--negative-out", type=Path)
    parser.add_argument("--negative-seed", type=int, default=7, help="another seed: other voices, levels and noise")
    args = parser.parse_args(list(argv) if argv is not None else None)

    if args.negative_minutes > 0:
        if args.negative_out is None:
            parser.error("--negative-minutes needs --negative-out")
        write_negative(args.negative_minutes, args.negative_out, seed=args.negative_seed)
        return 0
    if args.set == "tests":
        specs, out = TEST_SET, args.out or DEFAULT_OUT
    elif args.set == "eval":
        specs, out = eval_set(), args.out or ROOT / "out" / "eval-audio"
    elif args.set == "spec":
        if args.spec is None or args.out is None:
            parser.error("--set spec needs --spec FILE and --out DIR")
        specs, out = load_spec_file(args.spec), args.out
    else:
        parser.error(f"unknown set {args.set!r}")
    if args.only:
        specs = [s for s in specs if s.id in set(args.only)]
    write_set(specs, out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
