"""Node `communication`: video calls with the user's contacts.

Contacts: Anna (daughter), Ben (son), Clara (neighbour), Dr. Weber (family doctor).
Names are matched case-insensitively and tolerantly ("Doctor Weber", "Dr Weber", "Weber",
"my daughter"), never by guessing: anything else is `unknown_contact`.

- RPC `start_call(contact)` -> `{"in_call": true, "contact", "relation"}`; already in a
  call with someone else -> `busy` (naming who); with the same contact -> success with
  `"already_in_call": true`.
- RPC `end_call()` -> `{"ended": true, "contact", "duration_s"}`; no call -> `not_in_call`.
- RPC `list_contacts()` -> `{"contacts": [{"name", "relation"}, ...]}`.
- RPC `get_call_state()` and topic `call_state` (on every change and at 1 Hz sim):
  `{"in_call": bool, "contact": str | None, "remote_speaking": bool, "duration_s": float | None}`.
  While a call runs the remote participant talks now and then (3 s of every 8 s) through
  the robot's speaker: `remote_speaking` lets the voice pipeline treat it like playback.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Mapping
from dataclasses import dataclass

from robovoice.errors import RobotFailure
from robovoice.middleware.base import JSON, ActionHandler, NodeHost, NodeInfo, RpcHandler, RpcInfo
from robovoice.sim.clock import SimClock
from robovoice.sim.node import check_args, make_node_info, str_arg

log = logging.getLogger(__name__)

NAME = "communication"
CALL_TOPIC = "call_state"
TICK_S = 0.25
HEARTBEAT_S = 1.0
SPEAKING_CYCLE_S = 8.0
SPEAKING_FROM_S = 0.5
SPEAKING_UNTIL_S = 3.5

RPCS = (
    RpcInfo("start_call", "rpc", ("contact",), "start a video call with a contact"),
    RpcInfo("end_call", "rpc", (), "end the video call"),
    RpcInfo("list_contacts", "rpc", (), "the contacts"),
    RpcInfo("get_call_state", "rpc", (), "whether a call is running, with whom"),
)
_RPC = {r.name: r for r in RPCS}


@dataclass(frozen=True, slots=True)
class Contact:
    name: str
    relation: str
    keys: frozenset[str]  # normalised names it answers to


CONTACTS: tuple[Contact, ...] = (
    Contact("Anna", "daughter", frozenset({"anna", "daughter"})),
    Contact("Ben", "son", frozenset({"ben", "son"})),
    Contact("Clara", "neighbour", frozenset({"clara", "neighbour", "neighbor"})),
    Contact("Dr. Weber", "family doctor",
            frozenset({"dr weber", "doctor weber", "weber", "doctor", "family doctor", "gp"})),
)

_LEADING = re.compile(r"^(?:my|the|our)\s+")
# a title before the name: "Dr. Weber", and a helper's "Sir Ben", "Ma'am Anna" (text test v70, audio v61),
# a Filipino family's "Tito Ben", "Ate Anna", "Doc Weber" (text test v78)
_TITLE = re.compile(r"^(?:dr|doctor|doc|dok|mr|mrs|ms|miss|sir|ma am|maam|madam|mister|auntie|aunty|uncle"
                    r"|tito|tita|kuya|ate|manong|manang|ninong|ninang|mommy|mom|mum|mama|daddy|papa)\s+")
# a word of endearment or respect after the name: "Anna beta", "Ben ji", "Anna dear" (text test v68), "Anna po"
# … and a Korean honorific or a relation said after the name: "Clara-ssi", "Ben samchon" (text test v105)
_ENDEARMENT = re.compile(r"\s+(?:beta|ji|didi|bhaiya|bhai|dear|love|darling|sweetie|po|ssi|nim|ya|ah|samchon|samchun"
                         r"|imo|gomo|oppa|unni|eonni|noona|nuna|hyung|hyeong)$")
# … and Gujarati's "-ben" (sister) joined to a name: "Clara-ben" (text test v132; "Anna Ben" is two names)
_SISTER = re.compile(r"(?<=\w)-(?:ben|behn|bahen)\b", re.IGNORECASE)


def _normalise(text: str) -> str:
    text = re.sub(r"[^a-z0-9]+", " ", text.lower()).strip()
    while (stripped := _LEADING.sub("", text)) != text:
        text = stripped
    return text


def find_contact(text: str) -> Contact | None:
    key = _normalise(_SISTER.sub("", text))
    candidates = {key, _TITLE.sub("", key), _ENDEARMENT.sub("", key)} - {""}
    found = next((c for c in CONTACTS if candidates & c.keys), None)
    if found is not None:
        return found
    # one contact's own name among other words: "Ben samchon, jebal" (a dev case of the forty-seventh
    # session); not a relation word ("my son's friend" is nobody here), nor two names
    named = [c for c in CONTACTS if re.search(rf"\b{_normalise(c.name).split()[-1]}\b", key)]
    return named[0] if len(named) == 1 else None


@dataclass(frozen=True, slots=True)
class _Call:
    contact: Contact
    started: float


class CommunicationNode:
    name = NAME

    def __init__(self, clock: SimClock) -> None:
        self._clock = clock
        self._call: _Call | None = None
        self._host: NodeHost | None = None

    @property
    def call_contact(self) -> str | None:
        return self._call.contact.name if self._call else None

    @property
    def remote_speaking(self) -> bool:
        if self._call is None:
            return False
        phase = (self._clock.now() - self._call.started) % SPEAKING_CYCLE_S
        return SPEAKING_FROM_S <= phase < SPEAKING_UNTIL_S

    def call_state(self) -> dict[str, JSON]:
        call = self._call
        return {
            "in_call": call is not None,
            "contact": call.contact.name if call else None,
            "remote_speaking": self.remote_speaking,
            "duration_s": round(self._clock.now() - call.started, 1) if call else None,
        }

    def node_info(self) -> NodeInfo:
        return make_node_info(NAME, RPCS, (CALL_TOPIC,))

    def rpc_handlers(self) -> Mapping[str, RpcHandler]:
        return {"start_call": self._start_call, "end_call": self._end_call,
                "list_contacts": self._list_contacts, "get_call_state": self._get_call_state}

    def action_handlers(self) -> Mapping[str, ActionHandler]:
        return {}

    async def run(self, host: NodeHost) -> None:
        """Publish `call_state` when it changes (checked at 4 Hz) and at least once a second."""
        self._host = host
        try:
            last_published: tuple[str | None, bool] | None = None
            last_time = float("-inf")
            async for now in self._clock.ticks(TICK_S):
                key = (self.call_contact, self.remote_speaking)
                if key != last_published or now - last_time >= HEARTBEAT_S - 1e-6:
                    host.publish(CALL_TOPIC, self.call_state())
                    last_published, last_time = key, now
        finally:
            self._host = None

    def _publish(self) -> None:
        if self._host is not None:
            self._host.publish(CALL_TOPIC, self.call_state())

    # --- handlers --------------------------------------------------------------------
    async def _start_call(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["start_call"])
        requested = str_arg(args, "start_call", "contact")
        contact = find_contact(requested)
        if contact is None:
            names = [c.name for c in CONTACTS]
            raise RobotFailure(
                f"no contact called {requested!r}; contacts: {', '.join(names)}",
                code="unknown_contact",
                hint="tell the user you cannot call them and name the contacts you can call",
                details={"contact": requested,
                         "contacts": [{"name": c.name, "relation": c.relation} for c in CONTACTS]},
            )
        result: dict[str, JSON] = {"in_call": True, "contact": contact.name, "relation": contact.relation}
        if self._call is not None:
            current = self._call.contact
            if current is contact:
                return {**result, "already_in_call": True}
            raise RobotFailure(
                f"already in a video call with {current.name}",
                code="busy",
                hint=f"ask the user whether to end the call with {current.name} first (end_video_call)",
                details={"in_call_with": current.name, "requested": contact.name},
            )
        self._call = _Call(contact, self._clock.now())
        log.info("video call with %s started", contact.name)
        self._publish()
        return result

    async def _end_call(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["end_call"])
        call = self._call
        if call is None:
            raise RobotFailure("there is no video call to end", code="not_in_call",
                               hint="tell the user no call is running")
        self._call = None
        duration = round(self._clock.now() - call.started, 1)
        log.info("video call with %s ended after %.0f s", call.contact.name, duration)
        self._publish()
        return {"ended": True, "contact": call.contact.name, "duration_s": duration}

    async def _list_contacts(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["list_contacts"])
        return {"contacts": [{"name": c.name, "relation": c.relation} for c in CONTACTS]}

    async def _get_call_state(self, args: dict[str, JSON]) -> JSON:
        check_args(args, _RPC["get_call_state"])
        return self.call_state()
