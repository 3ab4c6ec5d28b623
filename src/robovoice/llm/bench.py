"""Benchmark of the embedded model: load, warm-up, first-event latency, prefix-reuse savings.

`bench_local` returns numbers only (the CLI formats them). A turn's latency is
measured from the call to ``stream`` to its first event: the first `TextDelta`
of a spoken answer, or the first complete `ToolCallRequested`.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Sequence
from dataclasses import dataclass

from robovoice.assistant.metrics import percentile
from robovoice.llm.base import ChatMessage, Deadlines, TextDelta, ToolCallRequested, ToolSpec
from robovoice.llm.local import LocalLlamaBackend

SYSTEM_PROMPT = (
    "You are the voice assistant of a home robot that helps an older adult. "
    "Answer in one or two short sentences. Use the functions to act."
)


def _obj(**properties: dict[str, object]) -> dict[str, object]:
    return {"type": "object", "properties": properties, "required": list(properties)}


# The sim robot's tool surface (DESIGN.md §5), as the MCP server would offer it.
SIM_ROBOT_TOOLS: tuple[ToolSpec, ...] = (
    ToolSpec("navigate_to", "Drive to a known place in the home.", _obj(target={"type": "string"})),
    ToolSpec("get_navigation_targets", "List the known places.", _obj()),
    ToolSpec("cancel_navigation", "Stop the current drive.", _obj()),
    ToolSpec("return_to_dock", "Drive back to the charging dock.", _obj()),
    ToolSpec("stop_robot", "Stop all motion now.", _obj()),
    ToolSpec("set_projector_power", "Switch the projector on or off.", _obj(on={"type": "boolean"})),
    ToolSpec("start_video_call", "Start a video call with a contact.", _obj(contact={"type": "string"})),
    ToolSpec("end_video_call", "End the running video call.", _obj()),
    ToolSpec("list_contacts", "List the contacts that can be called.", _obj()),
    ToolSpec("get_battery_state", "Battery percent and whether it is charging.", _obj()),
    ToolSpec("get_robot_pose", "Where the robot is: x, y, heading, nearest place.", _obj()),
    ToolSpec("get_camera_image", "A picture from the robot's camera.", _obj()),
)

UTTERANCES: tuple[str, ...] = (
    "Please drive to the kitchen.",
    "Switch on the projector.",
    "Call my daughter Anna.",
    "What is your name?",
)


# A benchmark measures slowness rather than failing on it (a cold 12-tool prompt on a busy machine).
BENCH_DEADLINES = Deadlines(first_token_s=600.0, idle_s=120.0, total_s=1200.0)


@dataclass(frozen=True, slots=True)
class BenchTurn:
    utterance: str
    first_event_s: float
    total_s: float
    prompt_tokens: int
    cached_prompt_tokens: int
    prompt_eval_ms: float
    calls: tuple[str, ...]  # "name(arguments JSON)"
    text: str


@dataclass(frozen=True, slots=True)
class LocalBenchResult:
    load_s: float
    warm_up_s: float
    prefix_tokens: int  # the system prompt + tools, evaluated by warm_up
    cold: BenchTurn  # one turn from an empty cache
    turns: tuple[BenchTurn, ...]  # after warm_up
    first_event_median_s: float
    first_event_p95_s: float
    prompt_eval_cold_ms: float
    prompt_eval_warm_median_ms: float
    prefix_eval_saving: float  # 1 - warm/cold prompt-evaluation time


async def _turn(backend: LocalLlamaBackend, system_prompt: str, tools: Sequence[ToolSpec], text: str) -> BenchTurn:
    messages = [ChatMessage("system", system_prompt), ChatMessage("user", text)]
    start = time.perf_counter()
    first: float | None = None
    calls: list[str] = []
    spoken: list[str] = []
    async for event in backend.stream(messages, tools):
        if first is None:
            first = time.perf_counter() - start
        if isinstance(event, ToolCallRequested):
            calls.append(f"{event.name}({event.raw_arguments})")
        elif isinstance(event, TextDelta):
            spoken.append(event.text)
    total = time.perf_counter() - start
    stats = backend.last_turn
    return BenchTurn(
        text,
        first if first is not None else total,
        total,
        stats.prompt_tokens,
        stats.cached_prompt_tokens,
        stats.prompt_eval_ms,
        tuple(calls),
        "".join(spoken),
    )


async def bench_local(
    backend: LocalLlamaBackend | None = None,
    *,
    utterances: Sequence[str] = UTTERANCES,
    tools: Sequence[ToolSpec] = SIM_ROBOT_TOOLS,
    system_prompt: str = SYSTEM_PROMPT,
    repeats: int = 1,
) -> LocalBenchResult:
    """Load, one cold turn, warm-up, then every utterance ``repeats`` times from the warm prefix.

    A backend passed in is used as is (and left open); otherwise the default model is
    loaded and closed again.
    """
    own = backend is None
    # tool_bias is calibrated for the assistant's own prompt (docs/llm.md); this bench's short
    # prompt would turn its small-talk turn into a tool call, so it measures the model untilted;
    # the warm-up is timed evaluating the prefix, not reading a state kept from an earlier run
    llm = backend if backend is not None else LocalLlamaBackend(deadlines=BENCH_DEADLINES, tool_bias=0.0,
                                                                keep_prompt_state=False)
    try:
        load_s = await llm.load()
        await llm.reset_cache()
        cold = await _turn(llm, system_prompt, tools, utterances[0])
        await llm.reset_cache()
        warm = await llm.warm_up(system_prompt, tools)
        turns = [await _turn(llm, system_prompt, tools, text) for _ in range(max(1, repeats)) for text in utterances]
    finally:
        if own:
            await llm.aclose()
    latencies = [t.first_event_s for t in turns]
    warm_eval = statistics.median(t.prompt_eval_ms for t in turns)
    return LocalBenchResult(
        load_s=load_s,
        warm_up_s=warm.total_s,
        prefix_tokens=warm.prompt_tokens,
        cold=cold,
        turns=tuple(turns),
        first_event_median_s=statistics.median(latencies),
        first_event_p95_s=percentile(latencies, 95),
        prompt_eval_cold_ms=cold.prompt_eval_ms,
        prompt_eval_warm_median_ms=warm_eval,
        prefix_eval_saving=1 - warm_eval / cold.prompt_eval_ms if cold.prompt_eval_ms > 0 else 0.0,
    )
