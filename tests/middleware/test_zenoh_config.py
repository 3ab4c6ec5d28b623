"""`zenoh://` URIs, the key layout and the payload codec (no network)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from robovoice.errors import ConfigError, RobotFailure
from robovoice.middleware import open_middleware
from robovoice.middleware.base import Feedback, NodeInfo, RpcInfo
from robovoice.middleware.zenoh import ZenohMiddleware
from robovoice.middleware.zenoh_codec import (
    failure_from_bytes,
    failure_to_bytes,
    feedback_from_bytes,
    feedback_to_bytes,
    info_from_json,
    info_to_json,
)
from robovoice.middleware.zenoh_config import ZenohSettings
from robovoice.middleware.zenoh_keys import KeyLayout, escape, unescape


def test_bare_uri_is_a_loopback_peer_rendezvous() -> None:
    settings = ZenohSettings.from_uri("zenoh://")
    assert settings.mode == "peer" and settings.robot == "default"
    assert settings.connect_endpoints == ("tcp/127.0.0.1:7447",)
    assert settings.listen_endpoints == ("tcp/127.0.0.1:7447", "tcp/127.0.0.1:0")
    assert settings.json5_entries() == {
        "mode": "peer",
        "scouting/multicast/enabled": False,
        "connect/endpoints": ["tcp/127.0.0.1:7447"],
        "connect/timeout_ms": 3000,
        "connect/exit_on_failure": False,
        "listen/endpoints": ["tcp/127.0.0.1:7447", "tcp/127.0.0.1:0"],
        "listen/exit_on_failure": False,  # the rendezvous port may be held by another process
    }


def test_explicit_endpoints_and_parameters() -> None:
    settings = ZenohSettings.from_uri(
        "zenoh://127.0.0.1:7447?mode=peer&listen=tcp/127.0.0.1:7448&connect=tcp/10.0.0.2:7447,tcp/10.0.0.3:7447"
        "&scouting=multicast&robot=r2&must_connect=true&timeout=0.5")
    assert settings.robot == "r2" and settings.multicast_scouting and settings.must_connect
    assert settings.connect_endpoints == ("tcp/10.0.0.2:7447", "tcp/10.0.0.3:7447", "tcp/127.0.0.1:7447")
    assert settings.listen_endpoints == ("tcp/127.0.0.1:7448",)
    entries = settings.json5_entries()
    assert entries["listen/exit_on_failure"] is True and entries["connect/exit_on_failure"] is True
    assert entries["connect/timeout_ms"] == 500

    only = ZenohSettings.from_uri("zenoh://?listen=tcp/127.0.0.1:7448")
    assert only.rendezvous is None and only.connect_endpoints == () and only.listen_endpoints == (
        "tcp/127.0.0.1:7448",)


def test_client_mode_always_must_connect() -> None:
    settings = ZenohSettings.from_uri("zenoh://192.168.1.5:7447?mode=client")
    assert settings.must_connect and settings.listen_endpoints == ()
    assert settings.connect_endpoints == ("tcp/192.168.1.5:7447",)
    assert "connect tcp/192.168.1.5:7447" in settings.describe()


def test_config_file_is_the_base_and_only_named_parameters_override(tmp_path: Path) -> None:
    config = tmp_path / "zenoh.json5"
    config.write_text("{}")
    settings = ZenohSettings.from_uri(f"zenoh://?config={config}&robot=r1")
    assert settings.json5_entries() == {}
    assert settings.config_file == config and settings.robot == "r1"
    override = ZenohSettings.from_uri(f"zenoh://?config={config}&mode=client&connect=tcp/1.2.3.4:7447")
    assert override.json5_entries()["mode"] == "client"
    assert override.json5_entries()["connect/endpoints"] == ["tcp/1.2.3.4:7447"]


@pytest.mark.parametrize("uri, endpoint", [
    ("zenoh://tcp/127.0.0.1:7447", "tcp/127.0.0.1:7447"),  # Zenoh's own endpoint syntax, as users type it
    ("zenoh://tcp/127.0.0.1:7447/", "tcp/127.0.0.1:7447"),
    ("zenoh://127.0.0.1:7447/", "tcp/127.0.0.1:7447"),
    ("zenoh://udp/10.0.0.2:7450", "udp/10.0.0.2:7450"),
    ("zenoh://tcp/robot.local", "tcp/robot.local:7447"),
    ("zenoh://[::1]:7447", "tcp/[::1]:7447"),
    ("zenoh://tcp/[::1]:7448", "tcp/[::1]:7448"),
])
def test_endpoint_syntax_means_the_same_rendezvous(uri: str, endpoint: str) -> None:
    settings = ZenohSettings.from_uri(uri)
    assert settings.rendezvous == endpoint and settings.connect_endpoints == (endpoint,)
    assert settings.listen_endpoints[0] == endpoint


def test_the_two_spellings_configure_zenoh_identically() -> None:
    plain = ZenohSettings.from_uri("zenoh://127.0.0.1:7447?robot=r")
    zenohish = ZenohSettings.from_uri("zenoh://tcp/127.0.0.1:7447?robot=r")
    assert plain.json5_entries() == zenohish.json5_entries()


def test_config_file_must_exist(tmp_path: Path) -> None:
    config = tmp_path / "zenoh.json5"
    with pytest.raises(ConfigError, match="is not a file"):
        ZenohSettings.from_uri(f"zenoh://?config={config}")
    config.write_text("{}")
    assert ZenohSettings.from_uri(f"zenoh://?config={config}").config_file == config


@pytest.mark.parametrize("uri, message", [
    ("zenoh://?colour=red", "unknown option"),
    ("zenoh://tcp/127.0.0.1:99999", "port must be a number from 1 to 65535"),
    ("zenoh://tcp/", "expected zenoh://tcp/HOST:PORT"),
    ("zenoh://tcp/a/b:1", "expected zenoh://tcp/HOST:PORT"),
    ("zenoh://tls/127.0.0.1:7447", "zenoh://?connect=tls/127.0.0.1:7447"),
    ("zenoh://127.0.0.1:7447/robot", "unexpected path '/robot'"),
    ("zenoh://::1:7447", "in brackets"),
    ("zenoh://:7447", "the host is empty"),
    ("zenoh://user@host:7447", "no user name"),
    ("zenoh://127.0.0.1:0", "port must be a number from 1"),
    ("zenoh://host:7447#x", "unexpected '#x'"),
    ("zenoh:host", "not a zenoh:// URI"),
    ("zenoh://?listen=", "empty listen endpoint"),
    ("zenoh://?connect=tcp/1.2.3.4:7447,", "empty connect endpoint"),
    ("zenoh://?connect=1.2.3.4:7447", "is not PROTOCOL/ADDRESS"),
    ("zenoh://?connect=http/1.2.3.4:7447", "is not PROTOCOL/ADDRESS"),
    ("zenoh://?connect=tcp/1.2.3.4", "needs HOST:PORT"),
    ("zenoh://?connect=tcp/1.2.3.4:0", "port must be a number from 1"),
    ("zenoh://?listen=tcp/::1:7447", "in brackets"),
    ("zenoh://?mode", "needs a value"),
    ("zenoh://?must_connect=", "must_connect must be"),
    ("zenoh://?timeout=-1", "timeout must be"),
    ("zenoh://?timeout=nan", "timeout must be"),
    ("zenoh://?robot=", "robot must not be empty"),
    ("zenoh://?mode=server", "mode must be"),
    ("zenoh://?scouting=gossip", "scouting must be"),
    ("zenoh://?timeout=soon", "timeout must be"),
    ("zenoh://?must_connect=maybe", "must_connect must be"),
    ("zenoh://host:notaport", "HOST:PORT"),
    ("zenoh://?mode=client&listen=tcp/127.0.0.1:1", "client mode needs"),
    ("zenoh://?robot=a&robot=b", "given 2 times"),
])
def test_bad_uris_say_what_is_wrong(uri: str, message: str) -> None:
    with pytest.raises(ConfigError, match=re.escape(message)):
        ZenohSettings.from_uri(uri)


def test_open_middleware_picks_zenoh() -> None:
    middleware = open_middleware("zenoh://127.0.0.1:7999?robot=x")
    assert isinstance(middleware, ZenohMiddleware)
    assert middleware.uri == "zenoh://127.0.0.1:7999?robot=x"


def test_key_layout() -> None:
    keys = KeyLayout("my robot")
    assert keys.alive("navigation") == "robovoice/my%20robot/alive/navigation"
    assert keys.rpc("navigation", "drive_to") == "robovoice/my%20robot/node/navigation/rpc/drive_to"
    assert keys.goal("nav", "drive_to", "g1") == "robovoice/my%20robot/node/nav/action/drive_to/goal/g1"
    assert keys.topic("/robot/pose") == "robovoice/my%20robot/topic/%2Frobot%2Fpose"
    feedback = keys.feedback("nav/1", "drive to", "abc")
    parsed = keys.parse_goal(feedback, "feedback")
    assert parsed is not None and (parsed.node, parsed.action, parsed.goal_id) == ("nav/1", "drive to", "abc")
    assert keys.parse_goal(feedback, "cancel") is None
    assert keys.last_chunk(keys.alive("Küche*")) == "Küche*"
    for name in ("plain", "with space", "a/b", "*", "$x", "ü", "100%"):
        assert unescape(escape(name)) == name and "/" not in escape(name)
    with pytest.raises(ValueError):
        escape("")


def test_codec_round_trips() -> None:
    info = NodeInfo("nav", rpcs=(RpcInfo("go", "action", ("target",), "drive"),), topics=("pose",),
                    manifest={"node": "nav", "tools": []}, manifest_source="nav/mcp.json")
    assert info_from_json(info_to_json(info), "nav") == info
    assert info_from_json({"rpcs": ["ping"]}, "ext") == NodeInfo("ext", rpcs=(RpcInfo("ping"),))
    with pytest.raises(ValueError, match="liveliness token"):
        info_from_json({"name": "other"}, "nav")
    with pytest.raises(ValueError, match="kind"):
        info_from_json({"rpcs": [{"name": "x", "kind": "service"}]}, "nav")

    feedback = Feedback(1.5, 3.0, "half way", {"x": 1})
    assert feedback_from_bytes(feedback_to_bytes(feedback)) == feedback

    failure = RobotFailure("no", code="unknown_target", hint="try kitchen", details={"known": ["kitchen"]})
    back = failure_from_bytes(failure_to_bytes(failure), "nav.go")
    assert back.to_dict() == failure.to_dict()
    plain = failure_from_bytes(b"segfault in driver", "nav.go")
    assert plain.code == "internal_error" and "segfault" in plain.message
    odd = RobotFailure("x", details={"obj": object()})
    assert failure_from_bytes(failure_to_bytes(odd), "w").details["unserialisable_details"].startswith("{")
