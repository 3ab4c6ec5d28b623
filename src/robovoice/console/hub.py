"""The console's event hub: conversation events grouped into turns, fanned out to listeners.

Each WebSocket listener gets its own bounded queue (`subscribe`); a listener that falls
behind loses its oldest messages, never blocks the robot or the conversation. Messages:

- ``{"type": "event", "turn": N, "source": "typed"|"voice", "event": {"kind": ..., ...}}``
- ``{"type": "turn_end", "turn": N, "source": ..., "latency_ms": {...}, "answer": URL|null}``
- ``{"type": "state", "state": {...}}`` (the robot, from `watch.RobotWatcher`)
- ``{"type": "audit", "record": {...}}`` (a tool call the console made, `service.ConsoleAudit`)

Voice events are grouped into turns by what they say: a wake word (or a stop, or a
command heard without one) opens a turn; the end of the voice turn, an ignored utterance
or the robot's stop closes it.
"""

from __future__ import annotations

import asyncio
import itertools
import time
from collections import deque
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Literal

from robovoice.console.jsonable import event_json

Source = Literal["typed", "voice"]

_OPENS = frozenset({"WakeWordHeard", "StopHeard"})
_CLOSES = frozenset({"VoiceTurnFinished", "UtteranceIgnored", "RobotStopped"})


@dataclass
class TurnRecord:
    """One turn as the page shows it: its events in order, then its latency marks."""

    id: int
    source: Source
    started: float = field(default_factory=time.time)
    events: list[dict[str, Any]] = field(default_factory=list)
    open: bool = True
    latency_ms: dict[str, float] = field(default_factory=dict)
    answer: str | None = None

    def to_json(self) -> dict[str, Any]:
        return {"id": self.id, "source": self.source, "started": round(self.started, 3), "open": self.open,
                "events": list(self.events), "latency_ms": dict(self.latency_ms), "answer": self.answer}


class EventHub:
    """See the module docstring. `max_turns` recent turns are kept for `/api/state`."""

    def __init__(self, *, max_turns: int = 50, queue_size: int = 512) -> None:
        self._queue_size = queue_size
        self._listeners: set[asyncio.Queue[dict[str, Any]]] = set()
        self._turns: deque[TurnRecord] = deque(maxlen=max_turns)
        self._ids = itertools.count(1)
        self._voice_turn: TurnRecord | None = None
        self.dropped = 0

    # --- listeners ---------------------------------------------------------------------

    @contextmanager
    def subscribe(self) -> Iterator[asyncio.Queue[dict[str, Any]]]:
        """A queue of every message from now on, for the block's duration."""
        queue: asyncio.Queue[dict[str, Any]] = asyncio.Queue(self._queue_size)
        self._listeners.add(queue)
        try:
            yield queue
        finally:
            self._listeners.discard(queue)

    @property
    def listeners(self) -> int:
        return len(self._listeners)

    def broadcast(self, message: dict[str, Any]) -> None:
        for queue in self._listeners:
            while queue.full():  # a slow listener loses its oldest messages
                queue.get_nowait()
                self.dropped += 1
            queue.put_nowait(message)

    # --- turns ---------------------------------------------------------------------------

    def recent_turns(self, limit: int = 20) -> list[dict[str, Any]]:
        """The newest `limit` turns, oldest first."""
        return [t.to_json() for t in list(self._turns)[-limit:]]

    def open_turn(self, source: Source) -> TurnRecord:
        record = TurnRecord(next(self._ids), source)
        self._turns.append(record)
        return record

    def add(self, record: TurnRecord, event: object) -> dict[str, Any]:
        """Append `event` to `record` and tell the listeners; the event's JSON."""
        body = event_json(event)
        record.events.append(body)
        self.broadcast({"type": "event", "turn": record.id, "source": record.source, "event": body})
        return body

    def close_turn(self, record: TurnRecord, latency_ms: dict[str, float] | None = None,
                   answer: str | None = None) -> None:
        if not record.open:
            return
        record.open = False
        record.latency_ms = dict(latency_ms or {})
        record.answer = answer
        self.broadcast({"type": "turn_end", "turn": record.id, "source": record.source,
                        "latency_ms": record.latency_ms, "answer": answer})

    @property
    def voice_turn_open(self) -> bool:
        return self._voice_turn is not None and self._voice_turn.open

    def voice_event(self, event: object, *, answer_url: str | None = None) -> TurnRecord:
        """Place a voice pipeline event in its turn (see the module docstring)."""
        kind = type(event).__name__
        current = self._voice_turn
        if current is not None and kind in _OPENS:
            self.close_turn(current)
            current = None
        if current is None or not current.open:
            current = self._voice_turn = self.open_turn("voice")
        self.add(current, event)
        if kind in _CLOSES:
            latency = getattr(event, "latency_ms", None)
            marks: dict[str, float] = {}
            if isinstance(latency, Mapping):
                marks = {str(k): float(v) for k, v in latency.items()}
            elif isinstance(latency, float):
                marks = {"stop": latency}
            self.close_turn(current, marks, answer_url if kind == "VoiceTurnFinished" else None)
            self._voice_turn = None
        return current
