"""The session recording (issue 12): a stereo WAV aligned sample by sample with the input,
channel 1 the microphone, channel 2 the robot, from which the latency can be read with no
help from the pipeline's own clocks."""

from __future__ import annotations

import asyncio
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from robovoice.assistant.connect import connect_robot
from robovoice.audio.format import MODEL_FORMAT, AudioChunk, as_int16, silence
from robovoice.audio.wav import read_wav
from robovoice.config import RobotConfig
from robovoice.errors import AudioError
from robovoice.llm.fake_server import CallbackReply, FakeOpenAIServer, TextReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.voice.events import VoiceTurnFinished
from robovoice.voice.models import VoiceModels
from robovoice.voice.pipeline import VoicePipeline
from robovoice.voice.recording import STEREO, reply_latency, session_audio, write_session
from robovoice.voice.room import SimulatedRoom

from .voice_kit import ROOM_ECHO, TEST_AUDIO, EventLog, SettableTranscriber, join, keyword_router, wake_command

RATE = MODEL_FORMAT.rate
CLICK_AT = 3_217  # the input sample with the click (not on a chunk or frame boundary)
AGREE_S = 0.05  # the WAV's latency and the pipeline's agree this closely


def _input_with_click() -> tuple[AudioChunk, int]:
    """Silence with a one-sample click, then the wake tone and a command; (audio, end of the command)."""
    lead = np.zeros(round(0.6 * RATE), dtype=np.int16)
    lead[CLICK_AT] = 20_000
    command = wake_command(1.0)
    audio = join(AudioChunk(lead, MODEL_FORMAT), command, silence(MODEL_FORMAT, 0.2))
    return audio, lead.shape[0] + command.num_frames


@pytest.mark.timeout(90)
async def test_recording_lines_up_with_the_input_and_shows_the_pipelines_latency(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend,
    tmp_path: Path,
) -> None:
    server.push(TextReply("Hello there, I am listening."))
    transcriber.text = "Hey Jarvis, say hello."
    audio, command_end = _input_with_click()
    log = EventLog()
    async with connect_robot(RobotConfig(address="sim://?speed=20")) as link:
        room = SimulatedRoom(echo=ROOM_ECHO, record=True)  # real time, as `assist --input` plays files
        pipeline = VoicePipeline(fakes, backend, link.tools, source=room.mic, sink=room.speaker,
                                 reference=room.reference, observer=log)
        async with asyncio.TaskGroup() as group:
            group.create_task(pipeline.run(finish_timeout_s=15.0))
            try:
                speech = room.say(audio, gap_s=0.5)
                done = await log.wait_for(VoiceTurnFinished, timeout=60.0)
                await room.until(room.now + 0.3)
            finally:
                room.close()
    path = write_session(tmp_path / "session.wav", room, origin=speech.start)

    recorded = read_wav(path)
    assert recorded.format == STEREO
    mic, robot = as_int16(recorded.samples)[:, 0], as_int16(recorded.samples)[:, 1]
    first_robot = int(np.flatnonzero(np.abs(robot) > 300)[0])
    # channel 1 is the input, sample for sample, until the robot's echo joins it
    assert first_robot > command_end, "the robot spoke only after the command ended"
    assert mic[CLICK_AT] == 20_000 and np.count_nonzero(mic[:CLICK_AT]) == 0
    n = min(first_robot, audio.num_frames)
    assert np.array_equal(mic[:n], as_int16(audio.samples)[:n]) and not np.any(mic[n:first_robot])
    assert np.any(np.abs(mic[first_robot:]) > 300), "the robot's echo is on the microphone"
    # the latency read off the WAV alone agrees with the pipeline's, both from the last word
    assert not done.cancelled and done.result is not None
    from_last_word = done.result.metrics.from_speech_end()
    wav_latency = reply_latency(recorded)
    assert wav_latency is not None
    assert abs(wav_latency - (first_robot - command_end) / RATE) < 0.002
    assert from_last_word["first_audio"] / 1000 == pytest.approx(wav_latency, abs=AGREE_S), from_last_word
    # the old origin (the end-of-turn decision) comes after the last word by the end-of-turn silence
    decided = from_last_word["first_audio"] - done.latency_ms["first_audio"]
    assert 0.15 <= decided / 1000 <= 0.7, decided


def test_reply_latency_reads_the_wav_alone() -> None:
    n = 3 * RATE
    both = np.zeros((n, 2), dtype=np.int16)
    both[RATE // 2 : RATE, 0] = 5000  # the person speaks until 1.0 s
    both[RATE + 12_000 :, 1] = 4000  # the robot answers at 1.75 s
    both[RATE + 12_100 :, 0] = 2000  # ... and its echo reaches the microphone
    assert reply_latency(AudioChunk(both, STEREO)) == pytest.approx(0.75, abs=1 / RATE)
    both[:, 1] = 0
    assert reply_latency(AudioChunk(both, STEREO)) is None
    with pytest.raises(AudioError, match="2 channels"):
        reply_latency(silence(MODEL_FORMAT, 1.0))


def test_a_room_that_did_not_record_has_no_session() -> None:
    with pytest.raises(AudioError, match=r"record=True"):
        session_audio(SimulatedRoom(), origin=0.0)


@pytest.mark.integration
@pytest.mark.timeout(600)
async def test_assist_record_with_the_real_voice_models(tmp_path: Path) -> None:
    """`robovoice assist --input F.wav --record OUT.wav` as a user runs it (Piper's voice, the real
    wake word, Silero VAD, Moonshine; the fake vLLM server as the model): the WAV lines up with
    the input, and its latency agrees with the one printed from the last word."""
    clip = TEST_AUDIO / "wake_piper_projector.wav"
    out = tmp_path / "session.wav"
    async with FakeOpenAIServer(default=CallbackReply(keyword_router)) as server:
        proc = await asyncio.create_subprocess_exec(
            sys.executable, "-m", "robovoice.cli", "assist", "--robot", "sim", "--sim-speed", "10",
            "--llm", f"{server.base_url}#fake-model", "--input", str(clip), "--record", str(out),
            stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT)
        try:
            async with asyncio.timeout(500):
                stdout, _ = await proc.communicate()
        finally:
            if proc.returncode is None:
                proc.kill()
                await proc.wait()
    text = stdout.decode()
    assert proc.returncode == 0, text[-3000:]
    assert "→ set_projector_power(on=true)" in text and f"session recorded to {out}" in text
    printed = re.search(r"latency from end of speech: .*first audio (\d+) ms", text)
    assert printed is not None, text[-3000:]
    recorded = read_wav(out)
    heard = as_int16(read_wav(clip).samples)
    mic, robot = as_int16(recorded.samples)[:, 0], as_int16(recorded.samples)[:, 1]
    first_robot = int(np.flatnonzero(robot)[0])
    last_word = int(np.flatnonzero(np.abs(heard) > 328)[-1])  # -40 dBFS
    assert first_robot > last_word, "the robot spoke after the command"
    n = min(first_robot, heard.shape[0])
    assert np.array_equal(mic[:n], heard[:n]), "channel 1 is the input, sample for sample"
    # the pipeline's first_audio is when the audio reached the speaker; Piper's own leading
    # quiet (~50 ms) comes after it, so the audible latency is a little longer
    handed = reply_latency(recorded, robot_dbfs=-100.0)
    audible = reply_latency(recorded)
    assert handed is not None and audible is not None
    assert int(printed.group(1)) / 1000 == pytest.approx(handed, abs=AGREE_S), (printed.group(0), handed)
    assert 0.0 <= audible - handed <= 0.1


def test_write_session_names_a_missing_folder(tmp_path: Path) -> None:
    room = SimulatedRoom(record=True)
    with pytest.raises(AudioError, match="no folder"):
        write_session(tmp_path / "nope" / "s.wav", room, origin=0.0)


@pytest.mark.timeout(300)
async def test_assist_record_names_what_is_missing(tmp_path: Path) -> None:
    for args, message in ((["--mic", "--record", str(tmp_path / "s.wav")], "--record needs --input"),
                          (["--input", str(TEST_AUDIO / "wake_piper_projector.wav"), "--record",
                            str(tmp_path / "nope" / "s.wav")], f"no folder {tmp_path / 'nope'}; create it first")):
        proc = await asyncio.create_subprocess_exec(
            sys.executable, "-m", "robovoice.cli", "assist", "--robot", "sim", *args,
            stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT)
        async with asyncio.timeout(120):
            out, _ = await proc.communicate()
        assert proc.returncode == 1 and message in out.decode(), out.decode()[-2000:]
