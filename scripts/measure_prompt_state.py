"""Measure a cold start's warm-up of the embedded model with and without the prefix state kept
on disk (llm/prompt_state.py): the assistant's system prompt and the sim robot's tools,
evaluated by one backend (which saves the state), then read back by a second one started
afterwards with the same cache folder, `--rounds` times, each round in a fresh folder. Prints
each round and the medians, and the first answer of both backends to the same words (they
must be equal).

    .venv/bin/python scripts/measure_prompt_state.py [--rounds 3]
"""

from __future__ import annotations

import argparse
import asyncio
import os
import statistics
import tempfile
from pathlib import Path

from robovoice.assistant.connect import connect_robot
from robovoice.assistant.prompt import SYSTEM_PROMPT
from robovoice.config import RobotConfig
from robovoice.llm.base import ChatMessage, TextDelta, ToolCallRequested, ToolSpec
from robovoice.llm.local import LocalLlamaBackend
from robovoice.llm.model_store import resolve_model_path
from robovoice.llm.prompt_state import FOLDER

WORDS = "Please drive to the kitchen."


async def _start(cache: Path, tools: list[ToolSpec]) -> tuple[float, bool, str]:
    backend = LocalLlamaBackend(resolve_model_path(), cache_dir=cache)
    try:
        await backend.load()
        stats = await backend.warm_up(SYSTEM_PROMPT, tools)
        messages = [ChatMessage("system", SYSTEM_PROMPT), ChatMessage("user", WORDS)]
        said = [e.text if isinstance(e, TextDelta) else f"{e.name}({e.arguments})"
                async for e in backend.stream(messages, tools) if isinstance(e, TextDelta | ToolCallRequested)]
    finally:
        await backend.aclose()
    return stats.total_s, stats.from_disk, "".join(said)


async def main(rounds: int) -> None:
    async with connect_robot(RobotConfig(address="sim://")) as link:
        tools = await link.tools.specs()
    evaluated: list[float] = []
    loaded: list[float] = []
    for n in range(rounds):
        with tempfile.TemporaryDirectory() as folder:
            cache = Path(folder)
            cold_s, cold_disk, cold_said = await _start(cache, tools)
            size = sum(p.stat().st_size for p in (cache / FOLDER).glob("*.state"))
            warm_s, warm_disk, warm_said = await _start(cache, tools)
        assert not cold_disk and warm_disk and cold_said == warm_said, (cold_said, warm_said)
        evaluated.append(cold_s)
        loaded.append(warm_s)
        print(f"round {n + 1}: evaluated {cold_s:.2f} s, from disk {warm_s:.3f} s "
              f"(state {size / 1e6:.1f} MB), load {os.getloadavg()[0]:.2f}; both said {warm_said!r}")
    print(f"median: evaluated {statistics.median(evaluated):.2f} s, from disk {statistics.median(loaded):.3f} s")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    asyncio.run(main(parser.parse_args().rounds))
