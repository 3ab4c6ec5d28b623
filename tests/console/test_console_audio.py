"""Talking through /ws/audio with a real WebSocket client: push-to-talk, then a command without
the wake word ("Robot, go to the kitchen."), as 16 kHz int16 PCM; the real voice pipeline
(VAD, Whisper, Piper) and a scripted model; the robot's voice comes back on the socket."""

from __future__ import annotations

import asyncio
import json
import struct
from pathlib import Path
from typing import Any

import pytest
from websockets.asyncio.client import connect

from robovoice.audio.format import MODEL_FORMAT, convert
from robovoice.audio.wav import read_wav
from robovoice.console.voice import VoiceBridge
from robovoice.llm.fake_server import CallbackReply
from robovoice.voice.models import VoiceModels

from .console_testkit import next_message, running_console
from .test_console_browser import _route

CLIP = Path(__file__).parents[1] / "data" / "audio" / "cmd_piper_kitchen.wav"  # "Robot, go to the kitchen."
pytestmark = pytest.mark.timeout(180)  # the real voice models load (~5 s quiet, 15 s on a busy machine)


async def test_push_to_talk_over_the_audio_socket_drives_the_robot_and_speaks_back(voice_models: VoiceModels) -> None:
    def bridge(backend: Any, tools: Any) -> VoiceBridge:
        return VoiceBridge(lambda: voice_models, backend, tools)

    pcm = convert(read_wav(CLIP), MODEL_FORMAT).bytes + bytes(MODEL_FORMAT.frames(1.5) * 2)
    async with (running_console(default=CallbackReply(_route), voice=bridge) as run,
                connect(f"{run.ws_base}/ws/events") as events):
        voice = run.console.voice
        assert voice is not None
        async with asyncio.timeout(120):
            while voice.status()["state"] != "ready":
                await next_message(events, lambda m: m["type"] == "state")
        async with connect(f"{run.ws_base}/ws/audio") as mic:
            await mic.send(json.dumps({"type": "ptt"}))
            for i in range(0, len(pcm), 3200):  # 100 ms chunks
                await mic.send(pcm[i:i + 3200])
            called = await next_message(events, lambda m: m["type"] == "event" and m["event"]["kind"] == "ToolCalled",
                                        timeout=120)
            assert called["source"] == "voice" and called["event"]["arguments"] == {"target": "kitchen"}
            end = await next_message(events, lambda m: m["type"] == "turn_end" and m["source"] == "voice", timeout=120)
            assert end["answer"] == "/api/answers/1.wav" and "first_audio" in end["latency_ms"]
            async with asyncio.timeout(30):
                spoken = await mic.recv()
            assert isinstance(spoken, bytes) and struct.unpack("<I", spoken[:4])[0] > 8000 and len(spoken) > 1000
        heard = [e["kind"] for t in run.console.state()["turns"] for e in t["events"]]
        assert "WakeWordHeard" not in heard and "TranscriptReady" in heard  # no wake word: the button was it
