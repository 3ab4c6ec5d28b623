"""The console in a real browser: Debian's headless Chromium driven by Playwright (never a
downloaded browser), its microphone a WAV file through Chromium's fake media stream.

- a typed request: the page shows the `navigate_to` call and the robot on the map in the kitchen;
- "Hey Jarvis, go to the kitchen" spoken into the page (the real voice pipeline: wake word,
  VAD, Whisper; a scripted model) ends the same way; a screenshot of the page is taken.
"""

from __future__ import annotations

import re
import shutil
import wave
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from robovoice.console.voice import VoiceBridge
from robovoice.llm.fake_server import CallbackReply, ScriptedCall, TextReply, ToolCallReply
from robovoice.voice.models import VoiceModels

from ..installed import missing, require
from .console_testkit import running_console
from .test_console_api import GO_TO_KITCHEN

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
pytestmark = pytest.mark.timeout(180)  # the spoken test loads the real voice models (~5 s quiet, 15 s busy)
CLIP = Path(__file__).parents[1] / "data" / "audio" / "wake_piper_kitchen_pink20.wav"  # Hey Jarvis, kitchen
STEP_MS = 60_000
FLAGS = ["--no-sandbox", "--use-fake-ui-for-media-stream", "--use-fake-device-for-media-stream",
         "--autoplay-policy=no-user-gesture-required"]


@pytest.fixture
def playwright_api() -> ModuleType:
    """Playwright for Python and Debian's chromium (a missing one fails the test, naming the step)."""
    require(Path(CHROMIUM).exists(), "chromium", "Debian package chromium")
    try:
        import playwright.async_api as api
    except ImportError:
        missing("playwright", "pip install 'robovoice[console]'")
    return api


def _route(request: Any) -> Any:
    """A scripted model: a drive to the place the user named, then one sentence."""
    messages = request.messages
    if messages and messages[-1].get("role") == "tool":
        return TextReply("I am in the kitchen now.")
    if "kitchen" in request.last_user_text.lower():
        return ToolCallReply((ScriptedCall("navigate_to", {"target": "kitchen"}),))
    return TextReply("Sorry, I did not catch that.")


def _padded(clip: Path, out: Path, silence_s: float = 50.0) -> Path:
    """The clip, then silence: Chromium loops the file, and on a busy machine speech-to-text
    can take seconds; the command must not come round again (a barge-in) within the test."""
    with wave.open(str(clip), "rb") as src:
        params, frames = src.getparams(), src.readframes(src.getnframes())
    with wave.open(str(out), "wb") as dst:
        dst.setparams(params)
        dst.writeframes(frames + bytes(int(params.framerate * silence_s) * params.sampwidth * params.nchannels))
    return out


async def test_a_typed_request_shows_the_call_and_the_robot_in_the_kitchen(playwright_api: ModuleType) -> None:
    async with running_console(GO_TO_KITCHEN) as run, playwright_api.async_playwright() as pw:
        browser = await pw.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        try:
            page = await browser.new_page()
            errors: list[str] = []
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            await page.goto(f"{run.base}/")
            await page.wait_for_selector("#robot[data-place='charging dock']", timeout=STEP_MS)
            await page.wait_for_selector("#map .place.unreachable[data-place='balcony']", timeout=STEP_MS)
            await page.fill("#say-text", "please go to the kitchen")
            await page.click("#say-form button")
            await page.wait_for_selector(".turn.typed .ev.call[data-tool='navigate_to']", timeout=STEP_MS)
            assert "navigate_to(target=\"kitchen\")" in await page.inner_text(".turn.typed")
            await page.wait_for_selector("#robot[data-place='kitchen'][data-moving='false']", timeout=STEP_MS)
            await page.wait_for_selector(".turn.typed .latency", timeout=STEP_MS)
            await page.wait_for_selector("#audit tbody tr[data-tool='navigate_to']", timeout=STEP_MS)
            # tools by hand: the form generated from get_navigation_targets' schema (no fields)
            await page.select_option("#tool-select", "get_navigation_targets")
            await page.click("#tool-form button")
            await page.wait_for_function("document.querySelector('#tool-result').textContent.includes('kitchen')",
                                         timeout=STEP_MS)
            assert errors == []
        finally:
            await browser.close()


async def test_a_spoken_command_through_the_fake_microphone_drives_the_robot(
        playwright_api: ModuleType, voice_models: VoiceModels, tmp_path: Path) -> None:
    wav = _padded(CLIP, tmp_path / "hey-jarvis-kitchen.wav")

    def bridge(backend: Any, tools: Any) -> VoiceBridge:
        return VoiceBridge(lambda: voice_models, backend, tools)

    async with (running_console(default=CallbackReply(_route), voice=bridge) as run,
                playwright_api.async_playwright() as pw):
        browser = await pw.chromium.launch(executable_path=CHROMIUM,
                                           args=[*FLAGS, f"--use-file-for-fake-audio-capture={wav}"])
        try:
            context = await browser.new_context(viewport={"width": 1400, "height": 1000})
            page = await context.new_page()
            errors: list[str] = []
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            await page.goto(f"{run.base}/")
            await page.wait_for_selector("#voice-state.ok", timeout=STEP_MS)  # the voice models are loaded
            await page.click("#mic-toggle")
            await page.wait_for_selector("#mic-toggle.on", timeout=STEP_MS)
            call = await page.wait_for_selector(".turn.voice .ev.call[data-tool='navigate_to']", timeout=STEP_MS)
            assert call is not None and "target=\"kitchen\"" in await call.inner_text()
            heard = await page.inner_text(".turn.voice")
            assert re.search(r"wake word \(score [01]\.\d\d\)", heard) and "kitchen" in heard.lower()
            await page.wait_for_selector("#robot[data-place='kitchen'][data-moving='false']", timeout=STEP_MS)
            await page.wait_for_selector(".turn.voice .latency", timeout=STEP_MS)  # the turn ended, spoken
            assert run.console.voice is not None and run.console.voice.speaker.sent_s > 0.5
            assert await page.evaluate("window.robovoice.robotAudioS") > 0.5  # the robot's voice played in the page
            await page.wait_for_selector(".turn.voice audio", timeout=STEP_MS)  # its answer is playable
            await page.click("#mic-toggle")  # the microphone off before the file comes round again
            await page.fill("#say-text", "and now please go to the kitchen again")
            await page.click("#say-form button")
            await page.wait_for_selector(".turn.typed .latency", timeout=STEP_MS)
            await page.wait_for_selector(".turn.typed audio[src='/api/answers/typed-2.wav']", timeout=STEP_MS)
            await page.screenshot(path=str(tmp_path / "console.png"), full_page=True)
            assert errors == []
        finally:
            await browser.close()
