"""`LocalLlamaBackend`: the embedded model (llama-cpp-python, CPU), the same events as the rest.

* Loaded once (``chat_format="chatml-function-calling"``, n_ctx 4096, 2 threads by default) on
  the backend's own single-thread executor; every llama call runs there, and `ThreadStream`
  bridges its output into asyncio.
* Prompts follow `chatml_tools` (the chatml-function-calling format, rendered by us; see that
  module for why). A turn with tools first lets a grammar pick the head (``message:`` or
  ``functions.<name>:``): a message is then streamed token by token as `TextDelta`; calls are
  generated whole, each argument object constrained by its JSON schema, and yielded as
  `ToolCallRequested` as soon as each is complete. A turn without tools is streamed plain ChatML.
* The head decision right after the user's words can be tilted towards calling a tool by
  ``tool_bias`` (`local_head`); `decide_head` reports the untilted margin.
* Prefix reuse: llama.cpp keeps the key/value cache of the last evaluation and
  ``Llama.generate`` re-evaluates only what follows the longest common token prefix. `warm_up`
  evaluates the system prompt + tools once (or reads them back from disk: `prompt_state`), so the
  first real turn only evaluates the conversation. ``Usage.cached_prompt_tokens`` reports how
  many prompt tokens were reused.
* Speculation: `prefill` evaluates an expected turn's prompt (and decodes its tool call) inside
  the end-of-turn silence; a real turn with the same prompt reuses it (`local_speculation`).
"""

from __future__ import annotations

import asyncio
import importlib.util
import json
import logging
import os
import threading
import time
from collections.abc import AsyncGenerator, AsyncIterator, Callable, Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from robovoice.errors import LLMError, MissingDependencyError
from robovoice.llm import chatml_tools as fmt
from robovoice.llm import prompt_state
from robovoice.llm.base import (
    LOCAL_DEADLINES,
    ChatMessage,
    DeadlineExceededError,
    Deadlines,
    Finished,
    LLMEvent,
    TextDelta,
    ToolSpec,
    Usage,
    tool_call_from_raw,
)
from robovoice.llm.bridge import ThreadStream
from robovoice.llm.local_head import TOOL_BIAS, HeadDecision, HeadTilt, bias_for, head_token_ids
from robovoice.llm.local_speculation import Speculation, SpeculativePrefill
from robovoice.llm.local_turn import Turn, TurnStats
from robovoice.llm.model_store import INSTALL_HINT as MODEL_INSTALL_HINT
from robovoice.llm.model_store import default_cache_dir, default_model_ready, resolve_model_path
from robovoice.llm.text_calls import TextCallParser

log = logging.getLogger(__name__)

INSTALL_HINT = "pip install 'robovoice[llm]'"


def llama_cpp_available() -> bool:
    return importlib.util.find_spec("llama_cpp") is not None


def _import_llama() -> Any:
    # llama.cpp's CPU backend is built with OpenMP, whose threads spin while waiting. On a
    # 2-core robot computer shared with wake word, VAD and TTS, spinning threads starve each
    # other (measured: 20 tokens took 22.8 s instead of 3.7 s under load). Passive waiting
    # must be chosen before the OpenMP runtime loads; an explicit OMP_WAIT_POLICY wins.
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    try:
        import llama_cpp  # heavy and optional: imported when a model is loaded
    except ImportError as exc:
        raise MissingDependencyError("the embedded local LLM (llama-cpp-python)", INSTALL_HINT) from exc
    return llama_cpp


class LocalLlamaBackend(SpeculativePrefill):
    """The embedded llama.cpp model; cheap to construct, loads on `load()` or the first turn."""

    accepts_audio = False

    def __init__(
        self,
        model_path: Path | None = None,
        *,
        name: str = "local",
        n_threads: int = 2,
        n_ctx: int = 4096,
        deadlines: Deadlines = LOCAL_DEADLINES,
        max_tokens: int = 256,
        temperature: float = 0.0,
        # One call per model step by default: allowed more, the 1.5B model appends unrelated calls (pose, camera,
        # battery), tripling turn latency (eval set); the loop gives it another step for multi-step requests.
        max_calls_per_turn: int = 1,
        # Added to the call head's first-token logit when the model, given the user's words, picks between answering
        # and calling a tool (not after tool results): calibrated on the eval set (docs/llm.md); 0 = off,
        # negative values favour answering.
        tool_bias: float = TOOL_BIAS,
        cache_dir: Path | None = None,
        keep_prompt_state: bool = True,  # the warmed-up prefix kept on disk (llm/prompt_state.py)
    ) -> None:
        if not llama_cpp_available():
            raise MissingDependencyError("the embedded local LLM (llama-cpp-python)", INSTALL_HINT)
        if model_path is None and not default_model_ready(cache_dir):
            raise MissingDependencyError("the embedded LLM model", MODEL_INSTALL_HINT)
        self.name = name
        self.model_path = model_path
        self.n_threads = n_threads
        self.n_ctx = n_ctx
        self.deadlines = deadlines
        self.max_tokens = max_tokens
        self.temperature = temperature
        self.max_calls_per_turn = max_calls_per_turn
        self.tool_bias = tool_bias
        self.cache_dir = cache_dir
        self.keep_prompt_state = keep_prompt_state
        self.load_s: float | None = None
        self.last_turn = TurnStats()
        self._llama: Any = None
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix=f"llm-{name}")
        self._pending: asyncio.Future[None] | None = None
        self._speculation: Speculation | None = None
        self._streams = 0
        self._grammars: dict[str, Any] = {}
        self._head_ids: dict[tuple[str, ...], tuple[list[int], list[int]]] = {}
        self._kept: tuple[str, tuple[ToolSpec, ...]] | None = None  # what warm_up evaluated

    def __repr__(self) -> str:
        return f"LocalLlamaBackend({str(self.model_path or 'default model')!r}, n_threads={self.n_threads})"

    # -- model thread -----------------------------------------------------------------

    def _load_blocking(self) -> Any:
        if self._llama is None:
            llama_cpp = _import_llama()
            path = resolve_model_path(self.model_path, self.cache_dir)
            start = time.perf_counter()
            self._llama = llama_cpp.Llama(model_path=str(path), chat_format="chatml-function-calling", n_ctx=self.n_ctx,
                                          n_threads=self.n_threads, n_threads_batch=self.n_threads, verbose=False)
            self.load_s = time.perf_counter() - start
            log.info("loaded %s in %.2f s", path.name, self.load_s)
        return self._llama

    def _grammar(self, gbnf: str) -> Any:
        llama_cpp = _import_llama()
        if gbnf not in self._grammars:
            self._grammars[gbnf] = llama_cpp.LlamaGrammar.from_string(gbnf, verbose=False)
        return self._grammars[gbnf]

    def _schema_grammar(self, tool: ToolSpec) -> Any:
        llama_cpp = _import_llama()
        schema = json.dumps(dict(tool.parameters), sort_keys=True)
        if schema not in self._grammars:
            try:
                self._grammars[schema] = llama_cpp.LlamaGrammar.from_json_schema(schema, verbose=False)
            except (ValueError, RuntimeError, KeyError, NotImplementedError) as exc:
                log.warning("tool %s: schema not usable as a grammar (%s); any JSON allowed", tool.name, exc)
                self._grammars[schema] = llama_cpp.LlamaGrammar.from_string(
                    llama_cpp.llama_grammar.JSON_GBNF, verbose=False
                )
        return self._grammars[schema]

    def _decide_head(self, turn: Turn, prompt: str, tools: Sequence[ToolSpec], bias: float) -> HeadDecision:
        llama_cpp = _import_llama()
        key = tuple(t.name for t in tools)
        if key not in self._head_ids:
            self._head_ids[key] = head_token_ids(self._llama, tools)
        tilt = HeadTilt(*self._head_ids[key], bias)
        head = self._complete(
            turn,
            prompt,
            stream=False,
            max_tokens=16,
            grammar=self._grammar(fmt.head_grammar(tools)),
            logits_processor=llama_cpp.LogitsProcessorList([tilt]),
        )
        decided = fmt.parse_head(head["choices"][0]["text"], tools)
        margin = tilt.margin if tilt.margin is not None else float("nan")
        turn.stats.head_margin = margin
        log.debug("head %s (margin %+.2f, bias %+.2f)", decided.tool.name if decided.tool else "message",
                  margin, bias)
        return HeadDecision(decided, margin)

    def _perf(self) -> tuple[float, int]:
        llama_cpp = _import_llama()
        data = llama_cpp.llama_perf_context(self._llama._ctx.ctx)
        return float(data.t_p_eval_ms), int(data.n_p_eval)

    def _complete(self, turn: Turn, prompt: str, *, stream: bool, **kwargs: Any) -> Any:
        """One ``create_completion`` call, counting prompt tokens reused from the last evaluation."""
        llama = self._llama
        llama_cpp = _import_llama()
        tokens = llama.tokenize(prompt.encode("utf-8"), add_bos=False, special=True)
        if len(tokens) + 8 > self.n_ctx:
            raise LLMError(f"prompt of {len(tokens)} tokens does not fit the context of {self.n_ctx}")
        reused = 0
        for a, b in zip(llama.input_ids[: llama.n_tokens].tolist(), tokens, strict=False):
            if a != b:
                break
            reused += 1
        if turn.stats.prompt_tokens == 0:  # the first call of the turn: its prompt is the turn's prompt
            turn.stats.prompt_tokens = len(tokens)
            turn.stats.cached_prompt_tokens = min(reused, len(tokens) - 1)
        stop_flag = turn.stop
        return llama.create_completion(
            prompt=tokens,
            temperature=self.temperature,
            stream=stream,
            stopping_criteria=llama_cpp.StoppingCriteriaList([lambda _ids, _logits: stop_flag.is_set()]),
            **kwargs,
        )

    def _stream_text(self, turn: Turn, prompt: str, tools: Sequence[ToolSpec] = ()) -> Iterator[LLMEvent]:
        """A streamed answer. A call the model writes inside it (``functions.NAME:`` after a
        sentence: the format allows a message or calls, the small model sometimes writes both)
        becomes a call, as on the OpenAI path (`text_calls`), never words to speak."""
        reason = "stop"
        parser = TextCallParser([t.name for t in tools])
        for chunk in self._complete(turn, prompt, stream=True, max_tokens=self.max_tokens, stop=[fmt.IM_END]):
            choice = chunk["choices"][0]
            turn.stats.completion_tokens += 1
            if choice["text"] and (released := parser.feed(choice["text"])):
                yield TextDelta(released)
            if choice.get("finish_reason"):
                reason = str(choice["finish_reason"])
        rest, written = parser.finish()
        if rest:
            yield TextDelta(rest)
        stamp = int(time.time() * 1000)
        for index, call in enumerate(written):
            yield tool_call_from_raw(f"call_text_{index}_{call.name}_{stamp}", call.name, call.arguments)
        yield self._finished(turn, "tool_calls" if written else reason)

    def _calls(self, turn: Turn, prompt: str, first: ToolSpec, tools: Sequence[ToolSpec]) -> Iterator[LLMEvent]:
        tool: ToolSpec | None = first
        index = 0
        while tool is not None and index < self.max_calls_per_turn:
            prompt += f"{fmt.FUNCTION_PREFIX}{tool.name}:\n"
            done = self._complete(
                turn, prompt, stream=False, max_tokens=self.max_tokens, grammar=self._schema_grammar(tool)
            )
            arguments = done["choices"][0]["text"].strip()
            turn.stats.completion_tokens += int(done["usage"]["completion_tokens"])
            yield tool_call_from_raw(f"call_{index}_{tool.name}_{int(time.time() * 1000)}", tool.name, arguments)
            index += 1
            if index >= self.max_calls_per_turn:
                break  # no need to ask the model whether another call follows
            prompt += arguments + "\n"
            head = self._complete(
                turn, prompt, stream=False, max_tokens=16, grammar=self._grammar(fmt.next_call_grammar(tools))
            )
            tool = fmt.parse_head(head["choices"][0]["text"], tools).tool
        yield self._finished(turn, "tool_calls")

    def _finished(self, turn: Turn, reason: str) -> Finished:
        s = turn.stats
        return Finished(reason, Usage(s.prompt_tokens, s.completion_tokens, s.cached_prompt_tokens))

    def _turn_events(
        self, turn: Turn, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]
    ) -> Iterator[LLMEvent]:
        self._load_blocking()
        listed = fmt.listed_tools(messages, tools, self._kept)
        prompt = self._prompt(messages, tools)  # every kept tool listed; the grammar offers `tools`
        if not tools:  # with tools listed but none offered, the head is a message's
            yield from self._stream_text(turn, prompt + (fmt.MESSAGE_HEAD + "\n" if listed else ""), listed)
            return
        decided = self._decide_head(turn, prompt, tools, bias_for(messages, self.tool_bias)).head
        if decided.tool is None:  # "message" (or, never under the grammar, nothing)
            yield from self._stream_text(turn, prompt + fmt.MESSAGE_HEAD + "\n", tools)
        else:
            yield from self._calls(turn, prompt, decided.tool, tools)

    def _job(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]
    ) -> Callable[[threading.Event], Iterator[LLMEvent]]:
        """The producer run on the model thread: events, with timings and llama errors wrapped."""

        def produce(stop: threading.Event) -> Iterator[LLMEvent]:
            turn = Turn(stop)
            self.last_turn = turn.stats
            p_eval_ms, _ = self._perf() if self._llama is not None else (0.0, 0)
            try:
                for event in self._turn_events(turn, messages, tools):
                    if turn.stats.first_event_s is None:
                        turn.stats.first_event_s = time.perf_counter() - turn.start
                    yield event
            except (ValueError, RuntimeError) as exc:
                raise LLMError(f"{self.name}: llama.cpp failed: {exc}") from exc
            finally:
                turn.stats.total_s = time.perf_counter() - turn.start
                if self._llama is not None:
                    turn.stats.prompt_eval_ms = self._perf()[0] - p_eval_ms

        return produce

    # -- async API --------------------------------------------------------------------

    async def _settle(self) -> None:
        """Wait until the model thread has finished an abandoned turn (it stops at the next token)."""
        if self._pending is not None and not self._pending.done():
            await self._pending

    async def _run(self, job: Callable[[threading.Event], Iterator[LLMEvent]]) -> AsyncIterator[LLMEvent]:
        if self._pending is not None and not self._pending.done():
            # Still evaluating an abandoned turn's prompt: that wait counts against this turn.
            try:
                await asyncio.wait_for(asyncio.shield(self._pending), self.deadlines.first_token_s)
            except TimeoutError as exc:
                where = f"{self.name} (busy finishing an abandoned turn)"
                raise DeadlineExceededError("first_token", self.deadlines.first_token_s, where) from exc
        stream: ThreadStream[LLMEvent] = ThreadStream(
            self._executor,
            job,
            deadlines=self.deadlines,
            where=f"{self.name} ({self.model_path or 'default'})",
        )
        try:
            async for event in stream.run():
                yield event
        finally:
            self._pending = stream.pending

    async def load(self) -> float:
        """Load the model now (seconds taken); otherwise the first turn loads it."""
        await self._settle()
        await asyncio.get_running_loop().run_in_executor(self._executor, self._load_blocking)
        return self.load_s or 0.0

    def _warm_up_blocking(self, prefix: str) -> TurnStats:
        llama, turn = self._load_blocking(), Turn(threading.Event())
        tokens = llama.tokenize(prefix.encode("utf-8"), add_bos=False, special=True)
        folder = (self.cache_dir or default_cache_dir()) if self.keep_prompt_state else None
        p_eval_ms, _ = self._perf()
        turn.stats.from_disk = prompt_state.warm(llama, _import_llama(), folder, self.n_ctx, tokens,
                                                 lambda: self._complete(turn, prefix, stream=False, max_tokens=1))
        if turn.stats.from_disk:
            turn.stats.prompt_tokens = turn.stats.cached_prompt_tokens = len(tokens)
        turn.stats.prompt_eval_ms = self._perf()[0] - p_eval_ms
        turn.stats.total_s = time.perf_counter() - turn.start
        return turn.stats

    async def warm_up(self, system_prompt: str, tools: Sequence[ToolSpec]) -> TurnStats:
        """Load if needed and evaluate the unchanging prefix (system prompt + tools), so that
        turns with this system prompt and these tools start from it. Call again when they change."""
        await self._settle()
        prefix = fmt.render_system(system_prompt, tools)
        self._kept = (system_prompt, tuple(tools))
        loop = asyncio.get_running_loop()
        return await loop.run_in_executor(self._executor, self._warm_up_blocking, prefix)

    async def decide_head(self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]) -> HeadDecision:
        """Only the head decision of a turn (no message, no arguments): what the model would do
        first, with ``tool_bias`` where `stream` applies it, and the margin without it. For
        calibration and tests."""
        if not tools:
            raise ValueError("a head decision needs tools")
        await self._settle()
        prompt = self._prompt(messages, tools)

        def decide() -> HeadDecision:
            self._load_blocking()
            return self._decide_head(Turn(threading.Event()), prompt, tools, bias_for(messages, self.tool_bias))

        return await asyncio.get_running_loop().run_in_executor(self._executor, decide)

    async def reset_cache(self) -> None:
        """Forget the evaluated prefix (the next turn evaluates its whole prompt); for benchmarks."""
        await self._settle()
        self._speculation = None
        if self._llama is not None:
            await asyncio.get_running_loop().run_in_executor(self._executor, self._llama.reset)

    async def stream(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]
    ) -> AsyncGenerator[LLMEvent, None]:
        if any(m.has_audio for m in messages):
            raise LLMError(f"{self.name} takes text only; transcribe the audio first")
        self._streams += 1
        try:
            replay = await self._claim_speculation(messages, tools)
            if replay is not None:  # decoded in the end-of-turn silence, for exactly this prompt
                for event in replay:
                    yield event
                return
            async for event in self._run(self._job(messages, tools)):
                yield event
        finally:
            self._streams -= 1

    async def aclose(self) -> None:
        await self._settle()
        llama, self._llama = self._llama, None
        if llama is not None:
            await asyncio.get_running_loop().run_in_executor(self._executor, llama.close)
        self._executor.shutdown(wait=True)
