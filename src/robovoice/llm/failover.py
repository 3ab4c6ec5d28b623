"""`FailoverBackend`: an ordered chain of backends (e.g. edge → cloud → local).

Per turn, backends are tried in order. One that fails *before its first event*
(cannot connect, HTTP error, missed deadline, any `LLMError`) is skipped and
marked unhealthy with exponential backoff; while backing off it is not tried,
so a dead edge server costs one connect timeout, not one per turn. When its
backoff has expired it is tried again and, if it answers, is healthy again.
If every backend is backing off, the one due soonest is tried anyway (better
than refusing without trying). When all fail, `AllBackendsFailedError` (a
`BackendUnavailableError`) lists every reason; the assistant then says
`FALLBACK_MESSAGE`.

How long a backend may take is its own business (`Deadlines`: a refused connection fails
at once, a CPU server may think for a minute before its first token); the chain's
`first_event_timeout_s` is only a safety net for backends without deadlines.

Once a backend has yielded an event the turn belongs to it: a later failure is
raised (and marks it unhealthy) rather than replayed elsewhere, which would
duplicate speech or tool calls.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
from collections.abc import AsyncGenerator, Callable, Sequence
from dataclasses import dataclass

from robovoice.errors import BackendUnavailableError, ConfigError, LLMError
from robovoice.llm.base import ChatMessage, Deadlines, LLMBackend, LLMEvent, ToolSpec, has_audio

log = logging.getLogger(__name__)

BOUND_GRACE_S = 1.0  # the chain waits this much past a backend's own first-token deadline

FALLBACK_MESSAGE = "I can't reach my language model right now. Please try again in a moment."


class AllBackendsFailedError(BackendUnavailableError):
    """Every backend of the chain failed (or was skipped) this turn; ``reasons`` per backend."""

    def __init__(self, reasons: dict[str, str]) -> None:
        self.reasons = reasons
        detail = "; ".join(f"{name}: {reason}" for name, reason in reasons.items())
        super().__init__(f"no LLM backend could answer: {detail}")


@dataclass(frozen=True, slots=True)
class Backoff:
    """Delay before retrying a failed backend: initial_s · factor^(failures-1), capped at max_s."""

    initial_s: float = 2.0
    factor: float = 2.0
    max_s: float = 60.0

    def delay(self, failures: int) -> float:
        if failures <= 0:
            return 0.0
        return float(min(self.max_s, self.initial_s * self.factor ** (failures - 1)))


@dataclass(frozen=True, slots=True)
class BackendHealth:
    name: str
    healthy: bool
    consecutive_failures: int
    last_error: str | None
    next_retry_at: float | None  # on the chain's clock; None while healthy
    last_success_at: float | None


@dataclass(slots=True)
class _State:
    failures: int = 0
    last_error: str | None = None
    next_retry_at: float | None = None
    last_success_at: float | None = None


class FailoverBackend:
    """Tries its backends in order each turn; see the module docstring."""

    def __init__(
        self,
        backends: Sequence[LLMBackend],
        *,
        backoff: Backoff | None = None,
        clock: Callable[[], float] = time.monotonic,
        first_event_timeout_s: float | None = 30.0,
        name: str = "failover",
    ) -> None:
        if not backends:
            raise ConfigError("a failover chain needs at least one backend")
        names = [b.name for b in backends]
        if len(set(names)) != len(names):
            raise ConfigError(f"backend names in a failover chain must be unique, got {names}")
        self.backends = tuple(backends)
        self.backoff = backoff or Backoff()
        self.first_event_timeout_s = first_event_timeout_s
        self.name = name
        self._clock = clock
        self._states = {b.name: _State() for b in self.backends}

    @property
    def accepts_audio(self) -> bool:
        """True only if every backend takes audio; audio turns skip the ones that don't."""
        return all(b.accepts_audio for b in self.backends)

    def health(self) -> tuple[BackendHealth, ...]:
        out: list[BackendHealth] = []
        for backend in self.backends:
            s = self._states[backend.name]
            out.append(
                BackendHealth(
                    name=backend.name,
                    healthy=s.failures == 0,
                    consecutive_failures=s.failures,
                    last_error=s.last_error,
                    next_retry_at=s.next_retry_at,
                    last_success_at=s.last_success_at,
                )
            )
        return tuple(out)

    def _mark_failed(self, backend: LLMBackend, reason: str) -> None:
        state = self._states[backend.name]
        state.failures += 1
        state.last_error = reason
        delay = self.backoff.delay(state.failures)
        state.next_retry_at = self._clock() + delay
        log.warning("LLM backend %s failed (%s); retry in %.1f s", backend.name, reason, delay)

    def _mark_ok(self, backend: LLMBackend) -> None:
        state = self._states[backend.name]
        if state.failures:
            log.info("LLM backend %s is answering again", backend.name)
        state.failures = 0
        state.next_retry_at = None
        state.last_success_at = self._clock()

    def _candidates(self, audio: bool, reasons: dict[str, str]) -> list[LLMBackend]:
        now = self._clock()
        ready: list[LLMBackend] = []
        waiting: list[LLMBackend] = []
        for backend in self.backends:
            state = self._states[backend.name]
            if audio and not backend.accepts_audio:
                reasons[backend.name] = "does not accept audio input"
            elif state.next_retry_at is not None and now < state.next_retry_at:
                reasons[backend.name] = f"backing off for {state.next_retry_at - now:.1f} s after: {state.last_error}"
                waiting.append(backend)
            else:
                ready.append(backend)
        if not ready and waiting:
            soonest = min(waiting, key=lambda b: self._states[b.name].next_retry_at or 0.0)
            ready.append(soonest)
        return ready

    async def prefill(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec], *, decode: bool = True
    ) -> object:
        """A speculative prefill (`voice.speculate`) goes to the backend the next turn will try
        first, when that one can prefill (the embedded model); None otherwise. The chain wraps
        even a single backend, so without this the voice pipeline never prefilled."""
        candidates = self._candidates(has_audio(messages), {})
        prefill = getattr(candidates[0], "prefill", None) if candidates else None
        if prefill is None:
            return None
        result: object = await prefill(messages, tools, decode=decode)
        return result

    def _first_event_bound(self, backend: LLMBackend) -> float | None:
        """The chain's own bound on a backend's first event: a safety net behind the backend's
        deadlines, never shorter than they are (a CPU server may think for a minute), so the
        backend's own, more precise error is the one reported."""
        own = getattr(backend, "deadlines", None)
        if not isinstance(own, Deadlines) or self.first_event_timeout_s is None:
            return self.first_event_timeout_s
        return max(self.first_event_timeout_s, own.connect_s + own.first_token_s + BOUND_GRACE_S)

    async def stream(
        self, messages: Sequence[ChatMessage], tools: Sequence[ToolSpec]
    ) -> AsyncGenerator[LLMEvent, None]:
        reasons: dict[str, str] = {}
        for backend in self._candidates(has_audio(messages), reasons):
            async with contextlib.aclosing(backend.stream(messages, tools)) as events:
                bound = self._first_event_bound(backend)
                try:
                    async with asyncio.timeout(bound):
                        first = await anext(events)
                except StopAsyncIteration:
                    reason = "ended the stream without any event"
                except TimeoutError:
                    reason = f"no first event within {bound:g} s"
                except LLMError as exc:
                    reason = str(exc) or type(exc).__name__
                else:
                    self._mark_ok(backend)
                    yield first
                    try:
                        async for event in events:
                            yield event
                    except LLMError as exc:
                        self._mark_failed(backend, f"failed mid-stream: {exc}")
                        raise
                    return
                reasons[backend.name] = reason
                self._mark_failed(backend, reason)
        raise AllBackendsFailedError({b.name: reasons.get(b.name, "not tried") for b in self.backends})

    async def aclose(self) -> None:
        errors: list[BaseException] = []
        for backend in self.backends:
            try:
                await backend.aclose()
            except Exception as exc:  # close every backend even if one fails; re-raised below
                errors.append(exc)
        if errors:
            raise errors[0]
