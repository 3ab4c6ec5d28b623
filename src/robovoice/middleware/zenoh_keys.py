"""The Zenoh key layout of robovoice (documented in docs/zenoh.md; keep the two in step).

Everything of one robot lives under ``robovoice/<robot>``::

    robovoice/<robot>/alive/<node>                                liveliness token of a node
    robovoice/<robot>/client/<client>                             liveliness token of a client
    robovoice/<robot>/node/<node>/info                            queryable: the node's NodeInfo
    robovoice/<robot>/node/<node>/rpc/<rpc>                       queryable: one RPC
    robovoice/<robot>/node/<node>/action/<action>/goal/<goal>     queryable (on .../goal/*): start a goal
    robovoice/<robot>/node/<node>/action/<action>/feedback/<goal> publication: progress of a goal
    robovoice/<robot>/node/<node>/action/<action>/cancel/<goal>   publication: cancel a goal
    robovoice/<robot>/topic/<topic>                               publication: a topic message

Each ``<...>`` is one key chunk: the name percent-encoded as by ``urllib.parse.quote(name,
safe="")`` (ASCII letters, digits and ``-_.~`` stay as they are; everything else, ``/``
included, becomes ``%XX`` of its UTF-8 bytes), so any name maps to exactly one chunk and back.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from urllib.parse import quote, unquote

ROOT = "robovoice"
PROTOCOL_VERSION = 1
"""Bumped when the layout or the payloads change incompatibly (sent in every NodeInfo)."""


@lru_cache(maxsize=4096)
def escape(name: str) -> str:
    """One key chunk for `name` (see the module docstring). Cached: every call builds its
    key from a few names, and ``quote`` is a visible part of an RPC's cost."""
    if not name:
        raise ValueError("an empty name cannot be a Zenoh key chunk")
    return quote(name, safe="")


def unescape(chunk: str) -> str:
    return unquote(chunk)


@dataclass(frozen=True, slots=True)
class GoalKey:
    """The parts of a goal, feedback or cancel key."""

    node: str
    action: str
    goal_id: str


@dataclass(frozen=True, slots=True)
class KeyLayout:
    """The keys of one robot (``robovoice/<robot>/...``)."""

    robot: str = "default"

    @property
    def prefix(self) -> str:
        return f"{ROOT}/{escape(self.robot)}"

    # --- presence ----------------------------------------------------------------------
    def alive(self, node: str) -> str:
        return f"{self.prefix}/alive/{escape(node)}"

    def alive_all(self) -> str:
        return f"{self.prefix}/alive/*"

    def client(self, client_id: str) -> str:
        return f"{self.prefix}/client/{escape(client_id)}"

    def client_all(self) -> str:
        return f"{self.prefix}/client/*"

    def last_chunk(self, key: str) -> str:
        """The (unescaped) name at the end of an ``alive/<node>`` or ``client/<id>`` key."""
        return unescape(key.rsplit("/", 1)[-1])

    # --- a node's calls ----------------------------------------------------------------
    def node(self, node: str) -> str:
        return f"{self.prefix}/node/{escape(node)}"

    def info(self, node: str) -> str:
        return f"{self.node(node)}/info"

    def rpc(self, node: str, rpc: str) -> str:
        return f"{self.node(node)}/rpc/{escape(rpc)}"

    def action(self, node: str, action: str) -> str:
        return f"{self.node(node)}/action/{escape(action)}"

    def goal(self, node: str, action: str, goal_id: str) -> str:
        return f"{self.action(node, action)}/goal/{escape(goal_id)}"

    def goal_all(self, node: str, action: str) -> str:
        return f"{self.action(node, action)}/goal/*"

    def feedback(self, node: str, action: str, goal_id: str) -> str:
        return f"{self.action(node, action)}/feedback/{escape(goal_id)}"

    def feedback_all(self) -> str:
        """Feedback of every goal of every node (one subscriber per client session)."""
        return f"{self.prefix}/node/*/action/*/feedback/*"

    def cancel(self, node: str, action: str, goal_id: str) -> str:
        return f"{self.action(node, action)}/cancel/{escape(goal_id)}"

    def cancel_all(self, node: str) -> str:
        return f"{self.node(node)}/action/*/cancel/*"

    def parse_goal(self, key: str, kind: str) -> GoalKey | None:
        """Split a concrete ``.../node/<n>/action/<a>/<kind>/<goal>`` key; None if it is not one."""
        head = f"{self.prefix}/node/"
        if not key.startswith(head):
            return None
        parts = key[len(head):].split("/")
        if len(parts) != 5 or parts[1] != "action" or parts[3] != kind or "*" in key:
            return None
        return GoalKey(unescape(parts[0]), unescape(parts[2]), unescape(parts[4]))

    # --- topics ------------------------------------------------------------------------
    def topic(self, topic: str) -> str:
        return f"{self.prefix}/topic/{escape(topic)}"
