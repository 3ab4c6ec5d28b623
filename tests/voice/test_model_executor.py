"""`ModelExecutor`: one thread per model, calls in order, a stop check's call first (issue 14:
under load a spoken stop waited seconds behind transcriptions of television)."""

from __future__ import annotations

import asyncio
import threading

import pytest

from robovoice.voice.inference import ModelExecutor


async def test_an_urgent_call_goes_before_the_calls_still_waiting_and_a_cancelled_one_never_runs() -> None:
    executor = ModelExecutor("order-test")
    release = threading.Event()
    ran: list[str] = []

    def job(name: str) -> str:
        if name == "busy":
            release.wait(5)
        ran.append(name)
        return name

    try:
        busy = asyncio.ensure_future(executor.run(job, "busy"))
        await asyncio.sleep(0.05)  # "busy" is running on the model's thread
        waiting = [asyncio.ensure_future(executor.run(job, f"tv-{i}")) for i in range(3)]
        dropped = asyncio.ensure_future(executor.run(job, "dropped"))
        urgent = asyncio.ensure_future(executor.run_first(job, "stop"))
        await asyncio.sleep(0.05)
        dropped.cancel()
        release.set()
        assert await urgent == "stop"
        assert await asyncio.gather(busy, *waiting) == ["busy", "tv-0", "tv-1", "tv-2"]
        assert ran == ["busy", "stop", "tv-0", "tv-1", "tv-2"]  # the stop overtook three; "dropped" never ran
        assert executor.calls == 5
    finally:
        release.set()
        await executor.aclose()


async def test_a_failing_call_raises_in_its_caller_and_the_thread_goes_on() -> None:
    executor = ModelExecutor("error-test")

    def fail() -> None:
        raise ValueError("bad audio")

    try:
        with pytest.raises(ValueError, match="bad audio"):
            await executor.run(fail)
        assert await executor.run(lambda: 42) == 42
    finally:
        await executor.aclose()
    assert not any(t.name == "voice-error-test" for t in threading.enumerate())  # closed: no thread left
    with pytest.raises(RuntimeError, match="closed"):
        await executor.run(lambda: 1)
