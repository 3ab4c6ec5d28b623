"""`robovoice serve | tools | call | check-manifests` (robovoice.commands.robot)."""

from __future__ import annotations

import asyncio
import json
import shutil
import signal
import subprocess
import sys
from importlib import resources
from pathlib import Path

import pytest
from mcp import Client

from robovoice.cli import main
from robovoice.commands.robot import parse_arguments
from robovoice.errors import ConfigError

from .distributed.helpers import Child, free_port, robovoice

SIM_TOOLS = {
    "navigate_to", "get_navigation_targets", "cancel_navigation", "return_to_dock", "stop_robot",
    "set_projector_power", "start_video_call", "end_video_call", "list_contacts",
    "get_battery_state", "get_robot_pose", "get_camera_image",
} | {"get_map", "get_call_state", "get_projector_state"}  # + tools for people (the console), not the model
PLACES = ["kitchen", "living room", "bedroom", "bathroom", "hallway", "front door", "charging dock"]
BOUND_S = 30.0


@pytest.fixture(autouse=True)
def _state_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROBOVOICE_STATE_DIR", str(tmp_path / "state"))  # the default audit log goes here


def test_tools_json_lists_exactly_the_design_tools(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["tools", "--robot", "sim", "--json"]) == 0
    tools = json.loads(capsys.readouterr().out)
    assert {tool["name"] for tool in tools} == SIM_TOOLS and len(tools) == len(SIM_TOOLS)
    for tool in tools:
        assert set(tool) <= {"name", "description", "inputSchema", "annotations", "_meta"}
        assert tool["description"] and tool["inputSchema"]["type"] == "object"
    navigate = next(t for t in tools if t["name"] == "navigate_to")
    assert navigate["inputSchema"]["required"] == ["target"]
    assert navigate["annotations"]["readOnlyHint"] is False


def test_tools_text_has_one_line_per_tool(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["tools", "--robot", "sim"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert sorted(line.split()[0] for line in lines) == sorted(SIM_TOOLS)
    assert any(line.startswith("navigate_to") and "(target)" in line for line in lines)


def test_call_unknown_target_is_an_error_listing_the_places(capsys: pytest.CaptureFixture[str],
                                                            tmp_path: Path) -> None:
    audit = tmp_path / "audit.jsonl"
    assert main(["call", "--robot", "sim", "navigate_to", "target=garage", "--json",
                 "--audit-log", str(audit)]) == 1
    result = json.loads(capsys.readouterr().out)
    assert result["isError"] is True
    error = json.loads(result["content"][0]["text"])
    assert error["error"] == "unknown_target" and error["details"]["known_places"] == PLACES
    assert result["structuredContent"] == error
    record = json.loads(audit.read_text())
    assert (record["tool"], record["node"], record["rpc"]) == ("navigate_to", "navigation", "drive_to")


def test_call_parses_values_as_json_and_writes_the_default_audit_log(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    assert main(["call", "--robot", "sim", "set_projector_power", "on=true"]) == 0
    assert json.loads(capsys.readouterr().out)["on"] is True
    assert main(["call", "--robot", "sim", "start_video_call", "contact=Dr. Weber"]) == 0
    assert "Dr. Weber" in capsys.readouterr().out
    records = (tmp_path / "state" / "audit.jsonl").read_text().splitlines()
    assert [json.loads(r)["arguments"] for r in records] == [{"on": True}, {"contact": "Dr. Weber"}]


def test_call_image_and_safety(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["call", "--robot", "sim", "get_camera_image", "--no-audit-log"]) == 0
    assert capsys.readouterr().out.startswith("[image image/jpeg, ")
    assert main(["call", "--robot", "sim", "set_max_speed", "mps=9", "--no-audit-log"]) == 1
    assert json.loads(capsys.readouterr().out)["error"] == "unknown_tool"


def test_parse_arguments() -> None:
    assert parse_arguments(["on=true", "n=3", "x=1.5", "target=living room", "s=\"3\"", "l=[1, 2]", "e="]) == {
        "on": True, "n": 3, "x": 1.5, "target": "living room", "s": "3", "l": [1, 2], "e": ""}
    with pytest.raises(ConfigError, match="key=value"):
        parse_arguments(["target"])
    with pytest.raises(ConfigError, match="key=value"):
        parse_arguments(["=kitchen"])
    with pytest.raises(ConfigError, match="'target' given twice"):
        parse_arguments(["target=kitchen", "target=bedroom"])


def _one_line_error(capsys: pytest.CaptureFixture[str]) -> str:
    captured = capsys.readouterr()
    assert "Traceback" not in captured.err
    lines = [line for line in captured.err.splitlines() if line.startswith("robovoice: error:")]
    assert len(lines) == 1, captured.err
    return lines[0]


def test_errors_are_one_clear_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    assert main(["call", "--robot", "sim", "navigate_to", "target"]) == 1
    assert "expected key=value" in _one_line_error(capsys)
    assert main(["serve", "--robot", "sim", "--transport", "http", "--host", "0.0.0.0"]) == 1
    assert "--token-file" in _one_line_error(capsys)
    assert main(["serve", "--robot", "sim", "--transport", "http", "--token-file", str(tmp_path / "nope")]) == 1
    assert "cannot read the token file" in _one_line_error(capsys)
    assert main(["tools", "--middleware", "bogus://x"]) == 1
    assert "supported schemes" in _one_line_error(capsys)
    assert main(["tools", "--robot", "sim", "--manifests", str(tmp_path / "missing")]) == 1
    assert "not a folder of manifests" in _one_line_error(capsys)


def _sim_manifests(tmp_path: Path) -> Path:
    folder = tmp_path / "manifests"
    shutil.copytree(str(resources.files("robovoice.sim").joinpath("manifests")), folder)
    return folder


def test_check_manifests(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    folder = _sim_manifests(tmp_path)
    assert main(["check-manifests", str(folder), "--robot", "sim"]) == 0
    assert capsys.readouterr().out.strip().endswith(f"{len(SIM_TOOLS)} tool(s): OK")
    navigation = folder / "navigation" / "mcp.json"
    navigation.write_text(navigation.read_text().replace('"rpc": "list_targets"', '"rpc": "list_target"'))
    assert main(["check-manifests", str(folder)]) == 0  # without live nodes the RPC names are not checked
    capsys.readouterr()
    assert main(["check-manifests", str(folder), "--robot", "sim"]) == 1
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == (f"{navigation}: $.tools[1].rpc: node 'navigation' offers no RPC or action 'list_target' "
                        "(fix: did you mean 'list_targets'? (known RPCs and actions of 'navigation': 'cancel', "
                        "'drive_to', 'get_status', 'list_targets'))")
    assert lines[-1].endswith("1 error")


async def test_serve_http_says_ready_serves_and_stops_on_sigterm(tmp_path: Path) -> None:
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "robovoice.cli", "serve", "--robot", "sim", "--transport", "http", "--port", "0",
        "--audit-log", str(tmp_path / "audit.jsonl"),
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE)
    try:
        assert process.stdout is not None
        async with asyncio.timeout(BOUND_S):
            line = (await process.stdout.readline()).decode()
        assert line.startswith("robovoice serve: ready: http://127.0.0.1:")
        assert line.rstrip().endswith(f"({len(SIM_TOOLS)} tools)")
        url = line.split()[3]
        async with Client(url) as client:
            assert {t.name for t in (await client.list_tools()).tools} == SIM_TOOLS
            assert not (await client.call_tool("list_contacts", {})).is_error
        process.send_signal(signal.SIGTERM)
        async with asyncio.timeout(BOUND_S):
            _, err = await process.communicate()
        assert process.returncode == 0, err.decode()
        assert b"Traceback" not in err
        assert json.loads((tmp_path / "audit.jsonl").read_text())["tool"] == "list_contacts"
    finally:
        if process.returncode is None:
            process.kill()
            await process.wait()


def test_output_into_a_closed_pipe_ends_quietly() -> None:
    """`robovoice tools --json | head -1`: the reader leaves early; no traceback."""
    proc = subprocess.Popen([sys.executable, "-m", "robovoice.cli", "tools", "--robot", "sim", "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.stdout is not None and proc.stderr is not None
    first = proc.stdout.readline()
    proc.stdout.close()  # like `head -1` exiting
    err = proc.stderr.read().decode()
    proc.stderr.close()
    proc.wait(timeout=BOUND_S)
    assert first.strip()
    assert "Traceback" not in err and "BrokenPipeError" not in err


# --- one robot address -------------------------------------------------------------------


def test_tools_takes_any_sim_address(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["tools", "--robot", "sim://", "--json"]) == 0
    assert {tool["name"] for tool in json.loads(capsys.readouterr().out)} == SIM_TOOLS
    assert main(["tools", "--robot", "sim://?speed=5&nodes=projector,communication", "--json"]) == 0
    assert {tool["name"] for tool in json.loads(capsys.readouterr().out)} == {
        "set_projector_power", "start_video_call", "end_video_call", "list_contacts"} | (
        SIM_TOOLS & {"get_projector_state", "get_call_state"})


def test_config_file_names_the_robot(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    config = tmp_path / "robovoice.toml"
    config.write_text('[robot]\naddress = "sim://?nodes=projector"\n')
    assert main(["tools", "--config", str(config), "--json"]) == 0
    assert {tool["name"] for tool in json.loads(capsys.readouterr().out)} == {"set_projector_power"} | (
        SIM_TOOLS & {"get_projector_state"})
    config.write_text('[robot]\nrobot = "sim"\nsim_speed = 4\n')
    assert main(["tools", "--config", str(config)]) == 1
    assert 'write address = "sim://?speed=4"' in _one_line_error(capsys)


@pytest.mark.parametrize("argv, message", [
    (["tools", "--robot", "turtle://"], "supported schemes are sim://, http://, https://, stdio:, memory://"),
    (["tools", "--robot", "sim://?speed=-2"], "speed must be greater than 0"),
    (["tools", "--robot", "sim://?sped=2"], "unknown option(s) sped"),
    (["tools", "--robot", "sim://?speed=2", "--sim-speed", "3"], "two sim speeds"),
    (["tools", "--middleware", "zenoh://127.0.0.1:7447", "--sim-speed", "3"], "--sim-speed applies to"),
    (["tools", "--robot", "sim", "--token-file", "t"], "token_file is for an http(s):// MCP server"),
    (["tools", "--robot", "http://127.0.0.1:1/mcp", "--manifests", "m"], "manifests apply to a robot served here"),
    (["tools", "--robot", "zenoh://tcp/127.0.0.1:99999"], "port must be a number from 1 to 65535"),
    (["tools", "--robot", "zenoh://tls/127.0.0.1:7447"], "cannot be the rendezvous"),
    (["tools", "--middleware", "sim://"], "is not a middleware URI"),
    (["tools", "--server", "zenoh://"], "--server takes an MCP server"),
    (["tools", "--robot", "http://127.0.0.1:8765"], "http://127.0.0.1:8765/mcp"),
    (["serve", "--robot", "http://127.0.0.1:8765/mcp"], "robovoice serve needs the robot's nodes in this process"),
    (["check-manifests", "somewhere", "--robot", "stdio:robovoice serve"], "checks against the nodes themselves"),
    (["sim", "--middleware", "memory://"], "no other process can reach"),
    (["tools", "--robot", "http://127.0.0.1:1/mcp", "--wait", "2"], "--wait applies to nodes on a middleware URI"),
    (["serve", "--port", "9000"], "--port applies to --transport http only"),
    (["serve", "--host", "0.0.0.0", "--allow-host", "robot.local"], "--host, --allow-host apply to --transport http"),
    (["sim", "--middleware", "sim://"], "is not a middleware URI"),
    (["sim", "--setup", "driving+dancing"], "known setups are driving, in_call, projector_on"),
    (["call", "--robot", "stdio:robovoice serve", "list_contacts", "--audit-log", "a.jsonl"],
     "--audit-log applies to a robot served here"),
])
def test_bad_robot_options_are_one_clear_line(capsys: pytest.CaptureFixture[str], argv: list[str],
                                              message: str) -> None:
    assert main(argv) == 1
    assert message in _one_line_error(capsys)


@pytest.mark.parametrize("argv, message", [
    (["tools", "--sim-speed", "-1"], "argument --sim-speed: expected a number greater than 0, not '-1'"),
    (["tools", "--sim-speed", "nan"], "argument --sim-speed: expected a number greater than 0"),
    (["tools", "--middleware", "memory://", "--wait", "-2"], "argument --wait: expected a number of seconds"),
    (["serve", "--port", "70000"], "argument --port: expected a port from 0"),
    (["serve", "--host", ""], "argument --host: expected a host name"),
    (["sim", "--speed", "0"], "argument --speed: expected a number greater than 0, not '0'"),
    (["chat", "--max-steps", "0"], "argument --max-steps: expected a whole number of at least 1"),
    (["bench", "mcp", "-n", "-5"], "argument -n: expected a whole number of at least 1"),
])
def test_bad_option_values_are_refused_by_the_parser(capsys: pytest.CaptureFixture[str], argv: list[str],
                                                     message: str) -> None:
    with pytest.raises(SystemExit) as exited:
        main(argv)
    assert exited.value.code == 2
    assert message in capsys.readouterr().err


def test_tools_and_call_of_an_mcp_server_over_stdio(capsys: pytest.CaptureFixture[str]) -> None:
    server = f"stdio:{sys.executable} -m robovoice.cli serve --robot sim://?speed=5 --no-audit-log"
    assert main(["tools", "--robot", server, "--json"]) == 0
    assert {tool["name"] for tool in json.loads(capsys.readouterr().out)} == SIM_TOOLS
    assert main(["call", "--server", server, "list_contacts"]) == 0
    assert "Dr. Weber" in capsys.readouterr().out


def _serve_http(*args: str) -> tuple[Child, str]:
    child = Child("serve", robovoice("serve", "--transport", "http", "--port", "0", "--no-audit-log", *args))
    line = child.wait_for_line("robovoice serve: ready: ", bound=BOUND_S)
    return child, line.split()[3]


def test_tools_and_call_of_a_running_server_over_http(capsys: pytest.CaptureFixture[str]) -> None:
    child, url = _serve_http("--robot", "sim://?speed=5")
    try:
        assert main(["tools", "--robot", url, "--json"]) == 0
        assert {tool["name"] for tool in json.loads(capsys.readouterr().out)} == SIM_TOOLS
        assert main(["call", "--server", url, "navigate_to", "target=garage"]) == 1
        assert "unknown_target" in capsys.readouterr().out
        dead = url.replace(url.split("/")[2], f"127.0.0.1:{free_port()}")
        assert main(["tools", "--robot", dead]) == 1
        assert "cannot reach the robot's MCP server at http://127.0.0.1:" in _one_line_error(capsys)
    finally:
        assert child.stop() == 0, child.output()


def test_sim_and_serve_meet_on_zenohs_own_endpoint_syntax(tmp_path: Path) -> None:
    """`zenoh://tcp/127.0.0.1:PORT` (Zenoh's syntax) is the same place as `zenoh://127.0.0.1:PORT`."""
    port = free_port()
    sim = Child("sim", robovoice("sim", "--middleware", f"zenoh://tcp/127.0.0.1:{port}?robot=meet",
                                 "--node", "projector"))
    try:
        sim.wait_for_line("robovoice sim: ready", bound=BOUND_S)
        serve, url = _serve_http("--middleware", f"zenoh://tcp/127.0.0.1:{port}?robot=meet", "--wait", "10")
        try:
            assert f"({len({'set_projector_power'} | (SIM_TOOLS & {'get_projector_state'}))} tools)" in serve.lines[-1]
            code = subprocess.run(robovoice("call", "--robot", url, "set_projector_power", "on=true"),
                                  capture_output=True, text=True, timeout=BOUND_S)
            assert code.returncode == 0 and '"on": true' in code.stdout, code.stderr
        finally:
            assert serve.stop() == 0, serve.output()
    finally:
        assert sim.stop() == 0, sim.output()


def test_sim_refuses_a_zenoh_uri_it_cannot_meet_anyone_on() -> None:
    for uri, form in (("zenoh://tls/127.0.0.1:7447", "zenoh://?connect=tls/127.0.0.1:7447"),
                      ("zenoh://127.0.0.1:7447/robot", "zenoh://HOST:PORT"),
                      ("zenoh://tcp/127.0.0.1:99999", "zenoh://tcp/127.0.0.1:7447")):
        done = subprocess.run(robovoice("sim", "--middleware", uri), capture_output=True, text=True, timeout=BOUND_S)
        assert done.returncode == 1 and form in done.stderr and "Traceback" not in done.stderr, done.stderr
        assert "ready" not in done.stdout
