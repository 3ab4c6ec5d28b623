"""Turn-taking: who has the floor, and what a heard utterance means. Pure logic.

Phases (`Phase`): LISTENING (waiting for the wake word), WOKEN (wake word heard, waiting
for the command), IN_TURN (a command is being answered), SPEAKING (the robot's speech is
playing), FOLLOW_UP (the robot just asked something: an answer needs no wake word).

Times are microphone stream times in seconds, passed in by the caller; nothing here reads
a clock. The pipeline feeds facts (`wake`, `turn_started`, `playback`, ...) and asks
`classify(utterance)` what to do with each utterance the VAD closed:

- COMMAND: it was addressed to the robot (the wake word fell inside it or shortly before,
  or it answers the robot's question) -> transcribe / send to the model;
- STOP_CHECK: not addressed, but the robot is moving and it is short: check for a spoken
  stop locally (no wake word is needed to stop a moving robot);
- IGNORE, with a reason.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from robovoice.voice.config import TurnTakingConfig


class Phase(Enum):
    LISTENING = "listening"
    WOKEN = "woken"
    IN_TURN = "in-turn"
    SPEAKING = "speaking"
    FOLLOW_UP = "follow-up"


class Action(Enum):
    COMMAND = "command"
    STOP_CHECK = "stop-check"
    IGNORE = "ignore"


@dataclass(frozen=True, slots=True)
class Verdict:
    action: Action
    reason: str = ""
    wake_at: float | None = None  # the wake word that addressed this command
    follow_up: bool = False
    wake_sure: bool = True  # false: an unsure wake word; the transcript must name the robot
    # the "wake word" is `TurnTaking.rearm`'s, set after a command turned away: nothing was heard
    # now, so the robot's own reply coming back counts as its own voice (voice/router.py)
    rearmed: bool = False


class TurnTaking:
    """The turn-taking state (see the module docstring)."""

    def __init__(self, config: TurnTakingConfig) -> None:
        self.config = config
        self._wake_at: float | None = None  # the last wake word not yet used by a command
        self._wake_sure = True
        self._rearmed = False  # the waiting wake word is `rearm`'s
        self._turn_running = False
        self._playing_until: float | None = None  # stream time the current playback ends (or None)
        self._playing = False
        self._follow_up_until: float | None = None
        self._asked = False

    # --- facts ---------------------------------------------------------------------------

    def wake(self, at: float, *, sure: bool = True) -> None:
        """The wake word was heard (and accepted) at `at`; an unsure one does not replace a
        sure one still waiting for its command."""
        if not sure and self._wake_at is not None and self._wake_sure:
            return
        self._wake_at, self._wake_sure, self._rearmed = at, sure, False
        self._follow_up_until = None

    def turn_started(self) -> None:
        self._turn_running = True
        self._follow_up_until = None

    def turn_finished(self, *, asked_question: bool) -> None:
        """The turn's model work is done (its speech may still be playing)."""
        self._turn_running = False
        self._asked = asked_question

    def turn_cancelled(self) -> None:
        self._turn_running = False
        self._asked = False

    def playback(self, playing: bool, at: float) -> None:
        """Whether the robot's speech is playing at stream time `at`. The end of playback of
        a finished turn that asked a question opens the follow-up window."""
        if playing:
            self._playing = True
            self._playing_until = None
            return
        if self._playing:
            self._playing = False
            self._playing_until = at
            if not self._turn_running and (self._asked or self.config.follow_up_always):
                self._follow_up_until = at + self.config.playback_tail_s + self.config.follow_up_s
            self._asked = False

    # --- queries ---------------------------------------------------------------------------

    def phase(self, now: float) -> Phase:
        if self._playing:
            return Phase.SPEAKING
        if self._turn_running:
            return Phase.IN_TURN
        if self._wake_at is not None and now - self._wake_at <= self.config.command_timeout_s:
            return Phase.WOKEN
        if self._follow_up_until is not None and now <= self._follow_up_until:
            return Phase.FOLLOW_UP
        return Phase.LISTENING

    @property
    def pending_wake(self) -> float | None:
        """The wake word waiting for its command, if any."""
        return self._wake_at

    @property
    def busy(self) -> bool:
        """A turn runs or speech plays: a wake word now is a barge-in."""
        return self._turn_running or self._playing

    def in_playback_tail(self, start: float) -> bool:
        """Whether speech starting at `start` began while the robot's last playback (or its
        echo tail) was still sounding."""
        if self._playing:
            return True
        return self._playing_until is not None and start < self._playing_until + self.config.playback_tail_s

    def expire(self, now: float, speaking_since: float | None = None) -> bool:
        """Forget a wake word nobody followed up within the timeout; True if one expired.
        `speaking_since`: the onset of the utterance still being said, if any. A command begun
        within the timeout keeps its wake word however long it runs: audio test v10's "Hey
        Jarvis, go to the bedroom, no, sorry, the kitchen, and then ring Clara." in babble was
        one 6.7 s utterance, and its end came after the wake word had expired."""
        wake = self._wake_at
        if wake is None or now - wake <= self.config.command_timeout_s:
            return False
        if speaking_since is not None and speaking_since - wake <= self.config.command_timeout_s:
            return False  # the command is still being said; its end decides (`classify`)
        self._wake_at = None
        return True

    def _wake_for(self, start: float, end: float) -> bool:
        # the wake word fell inside the utterance (or was confirmed just after it ended), or
        # came before it and the command followed within the timeout
        wake = self._wake_at
        return wake is not None and wake <= end + self.config.wake_slack_s and start - wake <= (
            self.config.command_timeout_s
        )

    def _follow_up_for(self, start: float) -> bool:
        return (
            self._follow_up_until is not None
            and start <= self._follow_up_until
            and not self._playing
            and not self.in_playback_tail(start)
        )

    def addressed(self, start: float, end: float) -> bool:
        """Whether an utterance from `start` to `end` would be a command (nothing consumed)."""
        return self._wake_for(start, end) or self._follow_up_for(start)

    def classify(self, start: float, end: float, *, moving: bool) -> Verdict:
        """What to do with the utterance from `start` to `end` (the wake word or follow-up
        window it uses is consumed)."""
        cfg = self.config
        if self._wake_for(start, end):
            wake, self._wake_at = self._wake_at, None
            return Verdict(Action.COMMAND, "wake word", wake_at=wake, wake_sure=self._wake_sure, rearmed=self._rearmed)
        if self._follow_up_for(start):
            self._follow_up_until = None
            return Verdict(Action.COMMAND, "follow-up", follow_up=True)
        if moving and end - start <= cfg.stop_max_s:
            return Verdict(Action.STOP_CHECK, "robot moving")
        return Verdict(Action.IGNORE, "no_wake_word")

    def rearm(self, at: float) -> None:
        """A command turned out to be the wake phrase alone, or was turned away as unsure: keep
        waiting for the command, which needs no wake word now."""
        # an unsure wake is named in its transcript by now
        self._wake_at, self._wake_sure, self._rearmed = at, True, True
