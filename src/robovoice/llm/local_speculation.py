"""The embedded model's speculative work inside the end-of-turn silence (`prefill`).

The voice pipeline calls ``prefill(messages, tools)`` with the first model step it expects
(from the speculative transcript, docs/voice.md "Using the end-of-turn silence"). On the
backend's own executor:

1. the prompt goes into llama.cpp's key/value cache: only what follows the prefix already
   cached, in chunks of `CHUNK_TOKENS`, so a stop takes effect within one chunk;
2. with ``decode``, when the model's head is a tool call the call is decoded too and its
   events are kept, keyed by the exact prompt and tool bias.

A real turn (`stream`) with the same prompt waits for that work and replays the kept events
(temperature 0: the same prompt gives the same call); with another prompt it stops the
speculation and starts from whatever prefix the two prompts share. A message head is not
decoded ahead (the real turn streams it, from the cached prompt). Nothing leaves the backend
before a real turn asks for it, so no tool is ever called speculatively.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections.abc import Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, replace
from typing import Any

from robovoice.errors import LLMError
from robovoice.llm import chatml_tools as fmt
from robovoice.llm.base import ChatMessage, DeadlineExceededError, Deadlines, LLMEvent, ToolSpec
from robovoice.llm.local_head import HeadDecision, bias_for
from robovoice.llm.local_turn import Turn, TurnStats

log = logging.getLogger(__name__)

CHUNK_TOKENS = 32  # prompt tokens per llama.cpp call while prefilling: a stop waits at most one chunk


@dataclass(frozen=True, slots=True)
class Prefilled:
    """What a `prefill` did: prompt tokens it evaluated (the rest was cached), whether it holds
    a decoded tool call for the real turn, whether it was stopped (a real turn with another
    prompt came), and its wall time."""

    evaluated_tokens: int
    decoded_call: bool
    stopped: bool
    seconds: float


@dataclass(slots=True)
class Speculation:
    key: str  # tool bias + rendered prompt: a real turn replays the events only for the same key
    stop: threading.Event
    future: asyncio.Future[None] | None = None
    events: tuple[LLMEvent, ...] | None = None
    stats: TurnStats | None = None
    evaluated: int = 0
    seconds: float = 0.0


def evaluate_prompt(llama: Any, tokens: Sequence[int], stop: threading.Event, chunk: int = CHUNK_TOKENS) -> int:
    """Bring llama.cpp's cache to `tokens` (a `llama_cpp.Llama`), evaluating only what follows
    the longest prefix already cached, chunk by chunk until `stop` is set; tokens evaluated."""
    if not tokens:
        return 0
    cached = llama.input_ids[: llama.n_tokens].tolist()
    common = 0
    for a, b in zip(cached, tokens, strict=False):
        if a != b:
            break
        common += 1
    if common == len(tokens) == llama.n_tokens:
        return 0  # exactly this prompt is cached and its last logits are current
    # at least the last token is evaluated again, so the logits are this prompt's
    llama.n_tokens = common = min(common, len(tokens) - 1)  # `Llama.eval` drops the cache past here
    llama._requires_eval = True  # the logits are stale until `eval` runs (it clears this)
    for i in range(common, len(tokens), chunk):
        if stop.is_set():
            return i - common
        llama.eval(tokens[i : i + chunk])
    return len(tokens) - common


class SpeculativePrefill:
    """`LocalLlamaBackend`'s speculative prefill (see the module docstring); a mixin that uses
    the backend's model thread, its head decision and its call decoding."""

    name: str
    n_ctx: int
    tool_bias: float
    deadlines: Deadlines
    last_turn: TurnStats
    _executor: ThreadPoolExecutor
    _pending: asyncio.Future[None] | None
    _speculation: Speculation | None = None
    _streams: int = 0  # real turns streaming now
    _kept: tuple[str, tuple[ToolSpec, ...]] | None  # what warm_up evaluated (`fmt.listed_tools`)

    # -- provided by the backend -----------------------------------------------------------

    def _load_blocking(self) -> Any:
        raise NotImplementedError

    def _decide_head(self, turn: Turn, prompt: str, tools: Sequence[ToolSpec], bias: float) -> HeadDecision:
        raise NotImplementedError

    def _calls(self, turn: Turn, prompt: str, first: ToolSpec, tools: Sequence[ToolSpec]) -> Iterator[LLMEvent]:
        raise NotImplementedError

    # ---------------------------------------------------------------------------------------

    def _speculation_key(self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]) -> str:
        return f"{bias_for(messages, self.tool_bias)!r}\n{self._prompt(messages, tools)}"

    def _prompt(self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]) -> str:
        """The prompt a real turn renders (every kept tool listed, `fmt.listed_tools`)."""
        return fmt.render_prompt(messages, fmt.listed_tools(messages, tools, self._kept))

    async def prefill(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec], *, decode: bool = True
    ) -> Prefilled | None:
        """Evaluate the prompt of the turn `messages` + `tools` ahead of it (and with `decode`,
        its tool call); waits for that work. None when nothing was started: a real turn is
        streaming (it is never delayed by a guess), or the messages carry audio."""
        if self._streams or any(m.has_audio for m in messages):
            return None
        key = self._speculation_key(messages, tools)
        spec = self._speculation
        if spec is None or spec.key != key:
            if spec is not None:
                spec.stop.set()
            spec = self._speculation = Speculation(key, threading.Event())
            prompt, bias = self._prompt(messages, tools), bias_for(messages, self.tool_bias)
            spec.future = asyncio.get_running_loop().run_in_executor(
                self._executor, self._speculate_blocking, spec, prompt, list(tools), bias, decode
            )
            self._pending = spec.future  # a real turn waits for it (or stops it) before its own work
        assert spec.future is not None
        await asyncio.shield(spec.future)
        return Prefilled(spec.evaluated, spec.events is not None, spec.stop.is_set(), spec.seconds)

    async def _claim_speculation(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]
    ) -> tuple[LLMEvent, ...] | None:
        """At the start of a real turn: the speculation's events when it decoded exactly this
        turn (after waiting for it to finish), else None, the speculation stopped if it was
        for another prompt (the turn's own job waits for it to stop: `_pending`)."""
        spec, self._speculation = self._speculation, None
        if spec is None:
            return None
        if spec.key != self._speculation_key(messages, tools):
            spec.stop.set()
            return None
        if spec.future is not None and not spec.future.done():
            try:  # the same work this turn would do: wait for it
                await asyncio.wait_for(asyncio.shield(spec.future), self.deadlines.first_token_s)
            except TimeoutError as exc:
                spec.stop.set()
                raise DeadlineExceededError("first_token", self.deadlines.first_token_s,
                                            f"{self.name} (speculative prefill)") from exc
        if spec.events is None or spec.stats is None:
            return None
        self.last_turn = replace(spec.stats, speculative=True, first_event_s=0.0)
        return spec.events

    def _speculate_blocking(
        self, spec: Speculation, prompt: str, tools: list[ToolSpec], bias: float, decode: bool
    ) -> None:
        started = time.perf_counter()
        try:
            llama = self._load_blocking()
            tokens = llama.tokenize(prompt.encode("utf-8"), add_bos=False, special=True)
            if len(tokens) + 8 > self.n_ctx:
                return  # the real turn reports it
            spec.evaluated = evaluate_prompt(llama, tokens, spec.stop)
            if spec.stop.is_set() or not decode or not tools:
                return
            turn = Turn(spec.stop)
            head = self._decide_head(turn, prompt, tools, bias).head
            if head.tool is None or spec.stop.is_set():
                return
            events = tuple(self._calls(turn, prompt, head.tool, tools))
            if not spec.stop.is_set():  # a stopped decode ends early: its call is cut short
                turn.stats.total_s = time.perf_counter() - started
                spec.events, spec.stats = events, turn.stats
        except (ValueError, RuntimeError, LLMError) as exc:  # a guess that failed costs nothing more
            log.warning("%s: speculative prefill failed: %s", self.name, exc)
        finally:
            spec.seconds = time.perf_counter() - started
            log.debug("%s: prefill of %d tokens%s in %.2f s", self.name, spec.evaluated,
                      " and a tool call" if spec.events else "", spec.seconds)
