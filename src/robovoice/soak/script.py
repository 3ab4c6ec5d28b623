"""The soak's commands: what is said, what follows it (a stop during the drive, a barge-in
while the robot talks) and how the outcome is judged from the sim robot and the events.

Kinds: ``drive`` (to a named place), ``question`` (battery, where are you), ``projector``,
``call`` (call Anna / end the call, by the sim's state), ``stop`` (a drive, then "Stop the
robot!" without the wake word while it moves), ``barge`` (a question with a long answer,
then the wake word and a battery question while the robot is still talking).

A robot at home keeps its battery up: when it is low (`DOCK_BELOW_PERCENT`) the next command
sends it to the charging dock, where the sim charges it. A drive the robot refuses for its
battery (``battery_low`` / ``battery_empty``) is done right only when the answer says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from robovoice.assistant.events import ToolCalled, ToolReturned
from robovoice.sim import SimState
from robovoice.voice.events import (
    BargedIn,
    PipelineEvent,
    RobotStopped,
    TranscriptReady,
    UtteranceIgnored,
    VoiceTurnFinished,
    WakeWordHeard,
    WakeWordRejected,
)

KINDS = ("drive", "question", "projector", "call", "stop", "barge")
WEIGHTS = (0.28, 0.2, 0.12, 0.14, 0.13, 0.13)
PLACES = ("kitchen", "living room", "bedroom", "bathroom", "hallway", "front door", "charging dock")
#: Far enough from anywhere for a stop to land mid-drive.
STOP_PLACES = ("front door", "kitchen", "bedroom", "living room")
DOCK = "charging dock"
#: Below this the person sends the robot to its dock (the sim refuses other drives below 5 %).
DOCK_BELOW_PERCENT = 20.0
BATTERY_REFUSALS = frozenset({"battery_low", "battery_empty"})
STOP_LINE = "Stop the robot!"
BARGE_LINE = "Hey Jarvis, how much battery do you have left?"
QUESTIONS = (("Hey Jarvis, how much battery do you have left?", "get_battery_state"),
             ("Hey Jarvis, where are you right now?", "get_robot_pose"))


@dataclass(frozen=True, slots=True)
class Command:
    """One scripted command: `kind`, the line said with the wake word, and what must happen
    (`tool` called; `place` reached; `projector_on` / `in_call` left in that state)."""

    kind: str
    say: str
    tool: str
    place: str | None = None
    projector_on: bool | None = None
    in_call: bool | None = None
    follow: str | None = None  # said after: the stop line, or the barge-in


def next_command(rng: np.random.Generator, state: SimState) -> Command:
    """A random command that makes sense in the robot's current state (the dock when its
    battery is low)."""
    if state.battery_percent < DOCK_BELOW_PERCENT and state.nearest_place != DOCK and not state.moving:
        return Command("drive", f"Hey Jarvis, go to the {DOCK}.", "navigate_to", place=DOCK)
    kind = str(rng.choice(KINDS, p=np.array(WEIGHTS) / sum(WEIGHTS)))
    if kind == "drive":
        place = str(rng.choice([p for p in PLACES if p != state.nearest_place]))
        return Command(kind, f"Hey Jarvis, go to the {place}.", "navigate_to", place=place)
    if kind == "question":
        text, tool = QUESTIONS[int(rng.integers(len(QUESTIONS)))]
        return Command(kind, text, tool)
    if kind == "projector":
        on = not state.projector_on
        return Command(kind, f"Hey Jarvis, switch the projector {'on' if on else 'off'}.", "set_projector_power",
                       projector_on=on)
    if kind == "call":
        if state.in_call:
            return Command(kind, "Hey Jarvis, end the call.", "end_video_call", in_call=False)
        return Command(kind, "Hey Jarvis, call Anna.", "start_video_call", in_call=True)
    if kind == "stop":
        place = str(rng.choice([p for p in STOP_PLACES if p != state.nearest_place]))
        return Command(kind, f"Hey Jarvis, go to the {place}.", "navigate_to", follow=STOP_LINE)
    return Command(kind, "Hey Jarvis, tell me about all the places in this home.", "get_battery_state",
                   follow=BARGE_LINE)


@dataclass
class Outcome:
    """What became of one command: `answered` (a turn finished with a reply, or the spoken
    stop reached the robot), `done` (the right thing happened), `problem` (why not)."""

    command: Command
    sim_at: float
    answered: bool = False
    done: bool = False
    problem: str | None = None
    barged_in: bool = False
    late: bool = False  # not idle within the turn timeout (then waited on, up to a hang bound)
    wall_s: float = 0.0
    calls: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)  # the tools' structured error codes
    reply: str = ""  # what the assistant answered (the last reply)

    def to_dict(self) -> dict[str, object]:
        return {"kind": self.command.kind, "said": self.command.say, "follow": self.command.follow,
                "sim_at_s": round(self.sim_at, 1), "answered": self.answered, "done": self.done,
                "problem": self.problem, "barged_in": self.barged_in, "late": self.late, "calls": self.calls,
                "errors": self.errors, "reply": self.reply, "wall_s": round(self.wall_s, 2)}


def _heard(events: list[PipelineEvent]) -> str:
    """What the pipeline heard instead, which says why a command came to nothing: no wake word,
    a wake word rejected as the robot's own voice, a transcript, or an utterance ignored and why
    (no_wake_word for a stop: heard when the robot no longer moved, so not checked for a stop)."""
    heard: list[str] = []
    for e in events:
        match e:
            case WakeWordHeard():
                heard.append(f"wake word at {e.at:.1f} s")
            case WakeWordRejected():
                heard.append(f"wake word at {e.at:.1f} s rejected as the robot's own voice")
            case TranscriptReady():
                heard.append(f"transcript {e.text!r}")
            case UtteranceIgnored():
                said = "" if e.text is None else f" {e.text!r}"
                heard.append(f"{e.reason}{said} at {e.start:.1f}-{e.end:.1f} s")
    return f" (heard: {'; '.join(heard)})" if heard else " (heard: nothing)"


def judge(outcome: Outcome, events: list[PipelineEvent], state: SimState) -> None:
    """Fill in `outcome` from the command's events and the robot's state afterwards."""
    cmd = outcome.command
    finished = [e for e in events if isinstance(e, VoiceTurnFinished)]
    replied = [e for e in finished if not e.cancelled and e.result is not None and e.result.reply.strip()]
    stops = [e for e in events if isinstance(e, RobotStopped)]
    outcome.calls = [e.name for e in events if isinstance(e, ToolCalled)]
    outcome.errors = [e.error for e in events if isinstance(e, ToolReturned) and e.error]
    outcome.reply = replied[-1].result.reply.strip() if replied and replied[-1].result else ""
    outcome.barged_in = any(isinstance(e, BargedIn) for e in events)
    if cmd.kind == "stop":
        outcome.answered = bool(stops) and stops[-1].ok
        problem: str | None = None
        if "navigate_to" not in outcome.calls:
            problem = "the drive never started"  # so the stop line was never said
        elif not outcome.answered:
            problem = "the spoken stop did not reach the robot" + _heard(events)
        if problem is None and state.moving:
            problem = "the robot is still moving after the stop"
        if problem is None and any(isinstance(e, ToolReturned) and e.name == "navigate_to" and not e.is_error
                                   for e in events):
            problem = "the drive arrived: the stop came after it had ended"
    else:
        outcome.answered = bool(replied)
        problem = None if outcome.answered else "no turn finished with a reply" + _heard(events)
        if problem is None and cmd.tool not in outcome.calls:
            problem = f"{cmd.tool} was not called (calls: {', '.join(outcome.calls) or 'none'})"
        refused = BATTERY_REFUSALS.intersection(outcome.errors)
        if problem is None and refused and cmd.place is not None:
            # the robot cannot drive: right only if the person is told why, not a silent "on my way"
            if "battery" not in outcome.reply.lower():
                problem = f"the drive was refused ({', '.join(sorted(refused))}) but the answer does not say why"
        elif problem is None and cmd.place is not None and (state.moving or state.nearest_place != cmd.place):
            problem = f"the robot is at the {state.nearest_place}, not the {cmd.place}"
        if problem is None and cmd.projector_on is not None and state.projector_on != cmd.projector_on:
            problem = f"the projector is {'on' if state.projector_on else 'off'}"
        if problem is None and cmd.in_call is not None and state.in_call != cmd.in_call:
            problem = "the call is still running" if state.in_call else "no call was started"
    outcome.problem = problem
    outcome.done = problem is None
