"""`robovoice bench console`: the page kept open for minutes, its memory and responsiveness.

The sim robot (pose topic at 10 Hz, camera at 3 Hz), the console (state to the page several
times a second, the camera picture ~3 Hz), a scripted model (the fake OpenAI server: no model
time) and headless Chromium (Debian's, through Playwright) with the page open. A typed request
sends the robot to another place every `drive_every_s`, so the map, the path, the conversation
and the audit log keep changing. Every `sample_s` it samples:

- the page: its JavaScript heap and DOM node count (Chrome DevTools ``Performance.getMetrics``)
  and how long a trivial ``page.evaluate`` takes (responsiveness);
- the server: this process's resident memory (the console, the sim, the MCP server);
- how old the robot's pose is on the page (state latency, from the page's own timestamps).

Memory is "flat" when the second half's least-squares slope is near zero; the figures are
printed as JSON. A measurement, not a test: nothing here asserts a goal.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import os
import shutil
import statistics
import time
from typing import Any

import httpx

from robovoice.assistant.connect import connect_robot
from robovoice.config import RobotConfig
from robovoice.console.serve import console_server
from robovoice.console.service import Console
from robovoice.errors import ConfigError
from robovoice.llm.fake_server import CallbackReply, FakeOpenAIServer, ScriptedCall, TextReply, ToolCallReply
from robovoice.llm.openai_compat import OpenAICompatBackend

PLACES = ("kitchen", "living room", "bedroom", "front door", "bathroom", "charging dock")


def _route(request: Any) -> Any:
    messages = request.messages
    if messages and messages[-1].get("role") == "tool":
        return TextReply("Done.")
    text = request.last_user_text.lower()
    place = next((p for p in PLACES if p in text), None)
    return ToolCallReply((ScriptedCall("navigate_to", {"target": place}),)) if place else TextReply("Sorry?")


def _rss_mb() -> float:
    with open(f"/proc/{os.getpid()}/statm") as statm:
        return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 1e6


def _slope_per_min(points: list[tuple[float, float]]) -> float:
    """Least-squares slope of (seconds, value) points, per minute (0 for fewer than 3)."""
    if len(points) < 3:
        return 0.0
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    var = sum((x - mx) ** 2 for x in xs)
    return 60.0 * sum((x - mx) * (y - my) for x, y in points) / var if var else 0.0


def _summary(name: str, samples: list[dict[str, Any]]) -> dict[str, Any]:
    values = [(s["t_s"], s[name]) for s in samples if s.get(name) is not None]
    if not values:
        return {}
    half = values[len(values) // 2:]
    return {"first": round(values[0][1], 2), "last": round(values[-1][1], 2),
            "max": round(max(v for _, v in values), 2),
            "slope_per_min_second_half": round(_slope_per_min(half), 3)}


async def bench_console(minutes: float = 10.0, *, sample_s: float = 10.0,
                        drive_every_s: float = 20.0) -> dict[str, Any]:
    from playwright.async_api import async_playwright

    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    if not os.path.exists(chromium):
        raise ConfigError("the console benchmark needs Debian's chromium (apt-get install chromium)")
    samples: list[dict[str, Any]] = []
    turns = 0
    async with (connect_robot(RobotConfig(address="sim://?speed=1")) as robot,
                FakeOpenAIServer(default=CallbackReply(_route)) as server):
        backend = OpenAICompatBackend(server.base_url, server.model)
        console = Console(robot.tools, backend, robot_name="sim://")
        watcher = asyncio.create_task(console.run(), name="bench-console")
        try:
            async with (console_server(console) as endpoint, async_playwright() as pw,
                        httpx.AsyncClient(base_url=f"http://127.0.0.1:{endpoint.port}", timeout=300) as http):
                browser = await pw.chromium.launch(executable_path=chromium, args=["--no-sandbox"])
                page = await browser.new_page(viewport={"width": 1400, "height": 1000})
                cdp = await page.context.new_cdp_session(page)
                await cdp.send("Performance.enable")
                await page.goto(f"http://127.0.0.1:{endpoint.port}/")
                await page.wait_for_selector("#robot")
                started = time.monotonic()
                places = itertools.cycle(PLACES)
                next_drive = next_sample = started
                pending: asyncio.Task[httpx.Response] | None = None
                while (now := time.monotonic()) - started < minutes * 60.0:
                    if now >= next_drive and (pending is None or pending.done()):
                        pending = asyncio.create_task(http.post("/api/say", json={"text": f"go to the {next(places)}"}))
                        turns += 1
                        next_drive = now + drive_every_s
                    if now >= next_sample:
                        t0 = time.perf_counter()
                        pose_age = await page.evaluate(
                            "window.robovoice.pose ? Date.now() / 1000 - window.robovoice.stateStamp : null")
                        evaluate_ms = (time.perf_counter() - t0) * 1000.0
                        metrics = {m["name"]: m["value"] for m in (await cdp.send("Performance.getMetrics"))["metrics"]}
                        samples.append({
                            "t_s": round(now - started, 1),
                            "page_heap_mb": metrics.get("JSHeapUsedSize", 0) / 1e6,
                            "page_dom_nodes": metrics.get("Nodes"),
                            "page_listeners": metrics.get("JSEventListeners"),
                            "server_rss_mb": _rss_mb(),
                            "evaluate_ms": round(evaluate_ms, 1),
                            "pose_age_s": round(pose_age, 3) if isinstance(pose_age, int | float) else None,
                        })
                        next_sample = now + sample_s
                    await asyncio.sleep(0.25)
                if pending is not None:
                    with contextlib.suppress(Exception):
                        await asyncio.wait_for(pending, 120)
                await browser.close()
        finally:
            watcher.cancel()
            await asyncio.gather(watcher, return_exceptions=True)
            await backend.aclose()
    evaluate = sorted(s["evaluate_ms"] for s in samples)
    ages = sorted(s["pose_age_s"] for s in samples if s["pose_age_s"] is not None)
    return {
        "minutes": minutes, "samples": len(samples), "typed_turns": turns, "watch_rounds": console.watcher.rounds,
        "page_heap_mb": _summary("page_heap_mb", samples), "page_dom_nodes": _summary("page_dom_nodes", samples),
        "page_listeners": _summary("page_listeners", samples), "server_rss_mb": _summary("server_rss_mb", samples),
        "evaluate_ms": {"p50": round(statistics.median(evaluate), 1), "max": evaluate[-1]} if evaluate else {},
        "pose_age_on_page_s": {"p50": round(statistics.median(ages), 3), "max": ages[-1]} if ages else {},
        "dropped_messages": console.hub.dropped, "load_average": list(os.getloadavg()),
    }
