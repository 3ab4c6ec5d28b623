"""What the embedded model measures about one turn (`TurnStats`) and the turn's own state on
the model thread (`Turn`): its stop flag and start time."""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass, field


@dataclass(slots=True)
class TurnStats:
    """Measured on the model thread for the last turn (or warm-up)."""

    prompt_tokens: int = 0
    cached_prompt_tokens: int = 0
    prompt_eval_ms: float = 0.0  # llama.cpp's own prompt-evaluation time, all calls of the turn
    first_event_s: float | None = None  # from job start to the first yielded event
    total_s: float = 0.0
    completion_tokens: int = 0
    # The head decision of the turn: logit of the best call-head token minus that of the best
    # message-head token, before ``tool_bias`` (None when the turn offered no tools).
    head_margin: float | None = None
    # The turn's first step was decoded speculatively, before the turn was asked for (its
    # events were replayed; `LocalLlamaBackend.prefill`).
    speculative: bool = False
    # A warm-up whose prefix state was read from disk, not evaluated (llm/prompt_state.py).
    from_disk: bool = False


@dataclass(slots=True)
class Turn:
    stop: threading.Event
    start: float = field(default_factory=time.perf_counter)
    stats: TurnStats = field(default_factory=TurnStats)
