"""A robot node written with nothing but `zenoh` and the key layout of docs/zenoh.md.

It stands for a node written in any language (Rust, C++, a ROS 2 adapter): it imports no
robovoice code. It offers two RPCs and a topic, announces its manifest, and the robovoice
MCP server turns them into the tools ``set_light``, ``list_lights`` and
``get_indoor_temperature`` as soon as it joins.

    python examples/zenoh_external_node.py --connect tcp/127.0.0.1:7447 [--robot default]

Prints ``lights: ready`` when announced; stops on SIGINT/SIGTERM. Needs only
``pip install eclipse-zenoh``.
"""

from __future__ import annotations

import argparse
import json
import signal
import threading
import time
from typing import Any
from urllib.parse import quote

import zenoh

NODE = "lights"
ROOMS = ("kitchen", "living room", "bedroom", "bathroom", "hallway")

MANIFEST = {
    "node": NODE,
    "description": "Ceiling lights of the home (an external Zenoh node).",
    "tools": [
        {
            "name": "set_light",
            "rpc": "set_light",
            "description": "Switch the ceiling light of a room on or off. Rooms: " + ", ".join(ROOMS) + ".",
            "parameters": {
                "type": "object",
                "properties": {
                    "room": {"type": "string", "description": "the room, e.g. \"kitchen\""},
                    "on": {"type": "boolean", "description": "true to switch on, false to switch off"},
                },
                "required": ["room", "on"],
            },
            "timeout_s": 5,
        },
        {"name": "list_lights", "rpc": "list_lights", "description": "Which room lights are on."},
    ],
    "snapshots": [
        {"name": "get_indoor_temperature", "topic": "temperature",
         "description": "The indoor temperature in degrees Celsius.", "max_age_s": 5},
    ],
}

INFO = {
    "protocol": 1,
    "name": NODE,
    "rpcs": [
        {"name": "set_light", "kind": "rpc", "params": ["room", "on"], "description": "switch a light"},
        {"name": "list_lights", "kind": "rpc", "params": [], "description": "the lights that are on"},
    ],
    "topics": ["temperature"],
    "manifest": MANIFEST,
    "manifest_source": f"{__file__} (MANIFEST)",
}


def key(*chunks: str) -> str:
    """A key of the layout: every name is one percent-encoded chunk."""
    return "/".join(quote(chunk, safe="") for chunk in chunks)


class Lights:
    def __init__(self, session: zenoh.Session, robot: str) -> None:
        self.session = session
        self.prefix = key("robovoice", robot)
        self.node = f"{self.prefix}/node/{key(NODE)}"
        self.on: set[str] = set()
        self.lock = threading.Lock()

    # Zenoh calls these on its own threads; this node needs no event loop.
    def on_info(self, query: zenoh.Query) -> None:
        with query:
            query.reply(f"{self.node}/info", json.dumps(INFO), encoding="application/json")

    def on_set_light(self, query: zenoh.Query) -> None:
        with query:
            args = json.loads(query.payload.to_bytes()) if query.payload else {}
            room = str(args.get("room", "")).strip().lower()
            if room not in ROOMS:
                fail(query, "unknown_room", f"there is no light in {room!r}",
                     hint="known rooms: " + ", ".join(ROOMS), details={"rooms": list(ROOMS)})
                return
            with self.lock:
                (self.on.add if args.get("on") else self.on.discard)(room)
                lights_on = sorted(self.on)
            reply(query, f"{self.node}/rpc/set_light", {"room": room, "on": room in lights_on})

    def on_list_lights(self, query: zenoh.Query) -> None:
        with query:
            with self.lock:
                lights_on = sorted(self.on)
            reply(query, f"{self.node}/rpc/list_lights", {"on": lights_on})

    def publish_temperature(self, celsius: float) -> None:
        self.session.put(f"{self.prefix}/topic/temperature", json.dumps({"celsius": round(celsius, 1)}),
                         encoding="application/json", attachment=json.dumps({"stamp": time.time()}))


def reply(query: zenoh.Query, reply_key: str, value: Any) -> None:
    query.reply(reply_key, json.dumps(value), encoding="application/json")


def fail(query: zenoh.Query, code: str, message: str, *, hint: str, details: dict[str, Any]) -> None:
    """An error the model can act on: a Zenoh error reply carrying robovoice's error body."""
    body = {"error": code, "message": message, "hint": hint, "details": details}
    query.reply_err(json.dumps(body), encoding="application/json")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--connect", action="append", default=[], help="Zenoh endpoint, e.g. tcp/127.0.0.1:7447")
    parser.add_argument("--robot", default="default", help="robot name (key prefix robovoice/<robot>)")
    parser.add_argument("--period", type=float, default=1.0, help="seconds between temperature messages")
    args = parser.parse_args()

    config = zenoh.Config()
    config.insert_json5("mode", '"peer"')
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("connect/endpoints", json.dumps(args.connect or ["tcp/127.0.0.1:7447"]))
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())

    with zenoh.open(config) as session:
        lights = Lights(session, args.robot)
        declared = [
            session.declare_queryable(f"{lights.node}/info", lights.on_info),
            session.declare_queryable(f"{lights.node}/rpc/set_light", lights.on_set_light),
            session.declare_queryable(f"{lights.node}/rpc/list_lights", lights.on_list_lights),
        ]
        # the liveliness token last: whoever sees it can fetch the info right away
        token = session.liveliness().declare_token(f"{lights.prefix}/alive/{key(NODE)}")
        print(f"{NODE}: ready", flush=True)
        while True:
            lights.publish_temperature(21.0 + (time.time() % 60) / 60)
            if stop.wait(args.period):
                break
        token.undeclare()  # type: ignore[no-untyped-call]  # zenoh 1.10 stub: no return type
        for entity in declared:
            entity.undeclare()  # type: ignore[no-untyped-call]  # (same)


if __name__ == "__main__":
    main()
