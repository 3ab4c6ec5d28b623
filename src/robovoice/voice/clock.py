"""Stream time -> the wall clock, for latencies measured from the user's last word.

The listener speaks in *stream time* (seconds of microphone audio, from the chunks'
timestamps): the VAD's utterance ends at its last voiced frame. Latencies are taken on the
wall clock (`time.perf_counter`). A microphone -- a sound card, or `SimulatedRoom` pacing a
WAV file at `speed` x real time -- delivers a chunk once its last sample has been captured,
never earlier, and sometimes later (a busy event loop, a front end that fell behind on a
loaded machine). So for every chunk ``received - end / speed`` is the wall time of stream
time 0 *plus* that chunk's delivery delay, and the smallest value seen so far is the best
estimate of the mapping itself. A source that runs faster than real time for a while (the
soak's, while nothing happens) only ever lowers that value, so the smallest is still the
present mapping when it paces again. No window: a front end that stays behind for many
seconds would otherwise move the mapping by its backlog.
"""

from __future__ import annotations

import math


class StreamAnchor:
    """Maps stream time to the wall clock from the chunks' arrival times (see the module docstring).

    `speed`: stream seconds per wall second of the source (1 for a microphone or a real-time
    room; `math.inf` for an unpaced source, which has no mapping: `wall_time` is then None).
    """

    def __init__(self, speed: float = 1.0) -> None:
        if not speed > 0:
            raise ValueError(f"stream speed must be positive, got {speed}")
        self.speed = speed
        self._origin: float | None = None  # the wall time of stream time 0, least delayed estimate

    def observe(self, received: float, stream_end: float) -> None:
        """A chunk ending at stream time `stream_end` arrived at wall time `received`."""
        if math.isinf(self.speed):
            return
        origin = received - stream_end / self.speed
        if self._origin is None or origin < self._origin:
            self._origin = origin

    def wall_time(self, stream_s: float) -> float | None:
        """The wall time at which stream time `stream_s` was captured; None before any chunk."""
        if self._origin is None:
            return None
        return self._origin + stream_s / self.speed
