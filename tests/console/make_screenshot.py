"""Make docs/console.png: the console in headless Chromium after a spoken and two typed requests.

    .venv/bin/python -m tests.console.make_screenshot docs/console.png

The robot is the sim at 2x; the model is scripted (the fake OpenAI server), the voice is real
(wake word, VAD, Whisper, Piper); the microphone is Chromium's fake one playing a test clip.
"""

from __future__ import annotations

import asyncio
import json
import sys
import tempfile
from pathlib import Path
from typing import Any

from playwright.async_api import async_playwright

from robovoice.config import RobotConfig
from robovoice.console.voice import VoiceBridge
from robovoice.llm.fake_server import CallbackReply, ScriptedCall, TextReply, ToolCallReply
from robovoice.voice.models import load_voice_models

from .console_testkit import running_console
from .test_console_browser import CHROMIUM, CLIP, FLAGS, _padded

PLACES = ("kitchen", "balcony", "living room")


def _route(request: Any) -> Any:
    messages = request.messages
    if messages and messages[-1].get("role") == "tool":
        body = json.loads(messages[-1].get("content") or "{}")
        if isinstance(body, dict) and body.get("error"):
            return TextReply(f"I can't go there: {body.get('message', 'it failed')}.")
        return TextReply("I'm on my way." if "living" in request.last_user_text else "I am in the kitchen now.")
    text = request.last_user_text.lower()
    for place in PLACES:
        if place in text:
            return ToolCallReply((ScriptedCall("navigate_to", {"target": place}),))
    return TextReply("Sorry, I did not catch that.")


async def make(out: Path) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        wav = _padded(CLIP, Path(tmp) / "clip.wav", silence_s=120.0)
        robot = RobotConfig(address="sim://?speed=2")

        def bridge(backend: Any, tools: Any) -> VoiceBridge:
            return VoiceBridge(load_voice_models, backend, tools)

        async with (running_console(default=CallbackReply(_route), voice=bridge, robot=robot) as run,
                    async_playwright() as pw):
            browser = await pw.chromium.launch(executable_path=CHROMIUM,
                                               args=[*FLAGS, f"--use-file-for-fake-audio-capture={wav}"])
            page = await browser.new_page(viewport={"width": 1400, "height": 1050})
            await page.goto(f"{run.base}/")
            await page.wait_for_selector("#voice-state.ok", timeout=120_000)
            await page.click("#mic-toggle")
            await page.wait_for_selector("#robot[data-place='kitchen'][data-moving='false']", timeout=180_000)
            await page.wait_for_selector(".turn.voice .latency", timeout=60_000)
            for request in ("Go to the balcony, please", "Then go to the living room"):
                await page.fill("#say-text", request)
                await page.click("#say-form button")
                await page.wait_for_selector(f".turn.typed .ev.user >> text={request}", timeout=60_000)
            await page.wait_for_function("window.robovoice.pose && window.robovoice.pose.x > 5.5", timeout=60_000)
            await page.select_option("#tool-select", "navigate_to")
            await page.fill("#tool-form input[name=target]", "bathroom")
            await page.screenshot(path=str(out), full_page=True)
            await page.wait_for_selector(".turn.typed:last-child .latency", timeout=60_000)  # the drive ends
            await browser.close()


if __name__ == "__main__":
    asyncio.run(make(Path(sys.argv[1] if len(sys.argv) > 1 else "docs/console.png")))
