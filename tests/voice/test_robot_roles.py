"""The robot's voice roles in the running pipeline: the stop, motion and pose tools come from
its manifests (renamed, missing, failing, stalling), and what is said about a tool follows its
manifest's phrases. Model fakes, the sim robot over a real MCP client, the fake vLLM server."""

from __future__ import annotations

import asyncio
import json
import logging
import shutil
import threading
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import pytest

import robovoice.sim
from robovoice.assistant.events import ToolReturned
from robovoice.assistant.motion_probe import PoseMotionProbe
from robovoice.assistant.robot_tools import ProgressCallback, RobotTools, ToolOutcome
from robovoice.audio.fakes import ToneSynthesizer
from robovoice.audio.format import AudioChunk
from robovoice.config import VoiceConfig
from robovoice.llm.base import ToolSpec
from robovoice.llm.fake_server import FakeOpenAIServer, ScriptedCall, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.manifest.voice import VoiceDecl
from robovoice.voice.events import RobotStopped, SentenceSpoken, StopHeard, UtteranceIgnored, VoiceTurnFinished
from robovoice.voice.models import VoiceModels
from robovoice.voice.roles import NO_STOP_WARNING

from .voice_kit import SettableTranscriber, babble, fake_models, voice_session, wake_command

pytestmark = pytest.mark.timeout(90)

SIM_MANIFESTS = Path(robovoice.sim.__file__).parent / "manifests"


def _base_manifest(tmp_path: Path, *, stop_name: str = "stop_robot", stop_role: bool = True) -> Path:
    """A manifest folder replacing the sim base's own: its stop tool renamed, or without a role."""
    folder = tmp_path / "manifests"
    shutil.copytree(SIM_MANIFESTS / "base", folder / "base")
    path = folder / "base" / "mcp.json"
    manifest = json.loads(path.read_text(encoding="utf-8"))
    stop = manifest["tools"][0]
    stop["name"] = stop_name
    if not stop_role:
        del stop["voice"]
    path.write_text(json.dumps(manifest), encoding="utf-8")
    return folder


class Interposed:
    """The robot's tools with one tool replaced: it fails, or hangs until released."""

    def __init__(self, inner: RobotTools, tool: str, *, fail: bool = False) -> None:
        self.inner = inner
        self.tool = tool
        self.fail = fail
        self.called = asyncio.Event()
        self.released = asyncio.Event()
        self.pending = False

    async def specs(self) -> list[ToolSpec]:
        return await self.inner.specs()

    def voice(self) -> Mapping[str, VoiceDecl]:
        return self.inner.voice()

    async def call(self, name: str, arguments: dict[str, Any], on_progress: ProgressCallback | None = None
                   ) -> ToolOutcome:
        if name != self.tool:
            return await self.inner.call(name, arguments, on_progress)
        self.called.set()
        if self.fail:
            body = {"error": "motors_locked", "message": "the motors do not answer", "hint": "", "details": {}}
            return ToolOutcome(json.dumps(body), True, 1.0, body)
        self.pending = True
        try:
            await self.released.wait()
        finally:
            self.pending = False
        return await self.inner.call(name, arguments, on_progress)


async def test_a_renamed_stop_tool_still_gets_the_local_spoken_stop(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer,
    backend: OpenAICompatBackend, tmp_path: Path,
) -> None:
    manifests = _base_manifest(tmp_path, stop_name="emergency_stop")
    async with voice_session(fakes, backend, speed=2.0, sim_speed=2.0, setup="driving",
                             manifests=manifests) as s:
        assert "emergency_stop" in [t.name for t in await s.tools.specs()]
        assert s.pipeline.roles.stop == "emergency_stop"
        transcriber.text = "Stop!"
        await s.say(babble(0.5))  # no wake word: the robot is moving
        stopped = await s.log.wait_for(RobotStopped, timeout=10)
        await s.settle()
        assert stopped.ok and not s.sim.state.moving
    assert s.log.of(StopHeard)[0].tool == "emergency_stop"
    assert server.requests == [], "the stop never went through the model"
    assert [e.text for e in s.log.of(SentenceSpoken) if e.kind == "stop"] == ["Stopped."]
    assert [c.name for r in s.pipeline.results for c in r.calls] == ["emergency_stop"]


async def test_a_robot_without_a_stop_tool_is_named_and_a_spoken_stop_says_so(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer,
    backend: OpenAICompatBackend, tmp_path: Path, caplog: pytest.LogCaptureFixture,
) -> None:
    manifests = _base_manifest(tmp_path, stop_role=False)
    with caplog.at_level(logging.WARNING, logger="robovoice.voice.pipeline"):
        async with voice_session(fakes, backend, speed=2.0, sim_speed=2.0, setup="driving",
                                 manifests=manifests) as s:
            transcriber.text = "Stop!"
            await s.say(babble(0.5))
            stopped = await s.log.wait_for(RobotStopped, timeout=10)
            await s.settle()
    assert NO_STOP_WARNING in caplog.text
    assert not stopped.ok and "no stop tool" in stopped.detail
    assert [e.text for e in s.log.of(SentenceSpoken) if e.kind == "stop"] == ["I could not stop the robot!"]


@pytest.mark.parametrize("how", ["fails", "times_out"])
async def test_a_stop_tool_that_fails_or_does_not_answer_is_said_plainly(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer,
    backend: OpenAICompatBackend, how: str,
) -> None:
    interposed: list[Interposed] = []

    def wrap(tools: RobotTools) -> Interposed:
        interposed.append(Interposed(tools, "stop_robot", fail=how == "fails"))
        return interposed[0]

    config = VoiceConfig(stop_timeout_s=0.5)
    async with voice_session(fakes, backend, speed=2.0, sim_speed=2.0, setup="driving", config=config,
                             tools=wrap) as s:
        transcriber.text = "Stop the robot."
        await s.say(babble(0.6))
        stopped = await s.log.wait_for(RobotStopped, timeout=10)
        await s.settle()
    assert interposed[0].called.is_set() and not stopped.ok
    assert ("motors do not answer" if how == "fails" else "did not answer within 0.5 s") in stopped.detail
    assert [e.text for e in s.log.of(SentenceSpoken) if e.kind == "stop"] == ["I could not stop the robot!"]
    returned = s.pipeline.results[-1].outcomes[0]
    assert returned.is_error and returned.error == ("motors_locked" if how == "fails" else "stop_failed")


async def test_the_microphone_loop_never_waits_for_the_pose_tool(
    fakes: VoiceModels, transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    interposed: list[Interposed] = []

    def wrap(tools: RobotTools) -> Interposed:
        interposed.append(Interposed(tools, "get_robot_pose"))
        return interposed[0]

    # a remote robot: whether it moves is asked from its pose tool (no local state), which hangs
    async with voice_session(fakes, backend, speed=2.0, sim_speed=2.0, setup="driving", sim_moving=False,
                             tools=wrap) as s:
        pose = interposed[0]
        assert s.pipeline.roles.pose == "get_robot_pose"
        s.pipeline.motion.probe = PoseMotionProbe(pose, "get_robot_pose", timeout_s=60.0)
        transcriber.text = "Stop!"
        s.room.say(babble(0.6))
        async with asyncio.timeout(10):
            await pose.called.wait()  # speech started: the pose tool was asked, and hangs
        heard_from = s.room.now
        ignored = await s.log.wait_for(UtteranceIgnored, timeout=10)
        await s.room.until(heard_from + 2.0, timeout=10)  # the microphone is read all the while
        assert pose.pending, "the pose tool still has not answered"
        assert ignored.reason == "no_wake_word"  # not known to move: no stop check, decided at once
        pose.released.set()  # it answers: the robot drives; the next short "stop" is checked
        async with asyncio.timeout(10):
            while not s.pipeline.motion.moving:
                await s.room.until(s.room.now + 0.08)
        await s.say(babble(0.5), gap_s=0.5)
        stopped = await s.log.wait_for(RobotStopped, timeout=10)
        await s.settle()
        assert stopped.ok and not s.sim.state.moving


async def test_pose_probe_reads_moving_from_the_sims_pose_tool_over_mcp() -> None:
    from robovoice.assistant.connect import connect_robot
    from robovoice.config import RobotConfig

    async with connect_robot(RobotConfig(address="sim://?speed=5")) as robot:
        assert robot.sim is not None
        probe = PoseMotionProbe(robot.tools, "get_robot_pose")
        assert await probe() is False
        await robot.sim.apply_setup("driving")
        async with asyncio.timeout(10):
            while not await probe():  # the pose snapshot (10 Hz) catches up with the drive
                pass
        assert probe.available
        missing = PoseMotionProbe(robot.tools, "no_such_tool")
        assert await missing() is None and not missing.available  # an error: never asked again
        assert await missing() is None
        listed = PoseMotionProbe(robot.tools, "get_navigation_targets")
        assert await listed() is None and not listed.available  # no "moving" in its answer


class _GatedVoice(ToneSynthesizer):
    """Tone speech whose acknowledgements wait (in the TTS thread) until `gate` opens."""

    def __init__(self) -> None:
        super().__init__(seconds_per_char=0.02)
        self.gate = threading.Event()

    def synthesize(self, text: str) -> AudioChunk:
        if text.startswith("On my way"):
            self.gate.wait(timeout=20)
        return super().synthesize(text)


async def test_an_acknowledgement_is_withdrawn_when_its_tool_fails_at_once(
    transcriber: SettableTranscriber, server: FakeOpenAIServer, backend: OpenAICompatBackend
) -> None:
    tts = _GatedVoice()
    models = fake_models(transcriber)
    models = type(models)(wake=models.wake, vad=models.vad, stt=models.stt, tts=tts,
                          playback_wake=models.playback_wake)
    server.push(ToolCallReply((ScriptedCall("navigate_to", {"target": "garage"}),)),
                TextReply("I don't know where the garage is."))
    async with voice_session(models, backend, speed=2.0) as s:
        transcriber.text = "Hey Jarvis, go to the garage."
        await s.say(wake_command())
        await s.log.wait_for(ToolReturned, timeout=30)  # at once: the acknowledgement is still being synthesised
        tts.gate.set()
        finished = await s.log.wait_for(VoiceTurnFinished, timeout=30)
        await s.settle()
    assert finished.result is not None and finished.result.outcomes[0].error == "unknown_target"
    spoken = [e.text for e in s.log.of(SentenceSpoken)]
    assert spoken == ["I don't know where the garage is."], "'On my way to the garage.' is never said"


class _ChangingTools:
    """A robot whose tool list changes (a node joins or leaves): a new list object each time."""

    def __init__(self, sections: dict[str, VoiceDecl]) -> None:
        self.sections = sections
        self._listed: list[ToolSpec] = []
        self.lists = 0

    def change(self, sections: dict[str, VoiceDecl]) -> None:
        self.sections = sections
        self._listed = []

    async def specs(self) -> list[ToolSpec]:
        if not self._listed:
            self.lists += 1
            self._listed = [ToolSpec(name, name, {"type": "object"}) for name in self.sections]
        return self._listed

    def voice(self) -> Mapping[str, VoiceDecl]:
        return self.sections

    async def call(self, name: str, arguments: dict[str, Any], on_progress: ProgressCallback | None = None
                   ) -> ToolOutcome:
        return ToolOutcome("{}", False, 0.0)


async def test_roles_follow_the_tool_list_and_a_missing_stop_tool_is_named(
    backend: OpenAICompatBackend, caplog: pytest.LogCaptureFixture
) -> None:
    from robovoice.voice.pipeline import VoicePipeline
    from robovoice.voice.room import SimulatedRoom

    tools = _ChangingTools({"halt": VoiceDecl(role="stop"), "drive": VoiceDecl(role="motion"),
                            "where": VoiceDecl(role="pose")})
    room = SimulatedRoom()
    pipeline = VoicePipeline(fake_models(), backend, tools, source=room.mic, sink=room.speaker)
    await pipeline.refresh_tools()
    assert (pipeline.roles.stop, pipeline.roles.motion, pipeline.roles.pose) == ("halt", frozenset({"drive"}), "where")
    assert pipeline.stopper.roles is pipeline.roles and pipeline.commands.roles is pipeline.roles
    assert pipeline.motion.probe is not None and pipeline.motion.probe.tool == "where"
    assert "halt" in pipeline.hint
    await pipeline.refresh_tools()
    assert tools.lists == 1, "an unchanged list is not fetched or rebuilt again"
    with caplog.at_level(logging.WARNING, logger="robovoice.voice.pipeline"):
        tools.change({"drive": VoiceDecl(role="motion")})  # the base node left
        await pipeline.refresh_tools()
    assert pipeline.roles.stop is None and pipeline.stopper.roles.stop is None
    assert NO_STOP_WARNING in caplog.text
    assert pipeline.motion.probe is None
    room.close()
