"""The committed test clips (tests/data/audio, made by scripts/make_audio_fixtures.py)."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from robovoice.audio.format import AudioChunk
from robovoice.audio.wav import read_wav

DATA = Path(__file__).resolve().parent.parent / "data" / "audio"


@dataclass(frozen=True)
class Clip:
    id: str
    text: str
    voice: str
    wake: bool
    snr_db: float | None
    noise: str | None
    speech_start_s: float
    speech_end_s: float
    path: Path

    def audio(self) -> AudioChunk:
        return read_wav(self.path)


def load_clips() -> list[Clip]:
    items: list[dict[str, Any]] = json.loads((DATA / "clips.json").read_text(encoding="utf-8"))
    return [
        Clip(
            id=i["id"],
            text=i["text"],
            voice=i["voice"],
            wake=i["wake"],
            snr_db=i.get("snr_db"),
            noise=i.get("noise"),
            speech_start_s=i["speech_start_s"],
            speech_end_s=i["speech_end_s"],
            path=DATA / f"{i['id']}.wav",
        )
        for i in items
    ]


CLIPS = load_clips()


def clip(clip_id: str) -> Clip:
    return next(c for c in CLIPS if c.id == clip_id)
