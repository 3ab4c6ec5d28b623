"""`robovoice serve | tools | call | check-manifests` (robovoice.commands.robot)."""

from __future__ import annotations

import asyncio
import json
import shutil
import signal
import sys
from importlib import resources
from pathlib import Path

import pytest
from mcp import Client

from robovoice.cli import main
from robovoice.commands.robot import parse_arguments
from robovoice.errors import ConfigError

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
        assert line.startswith("robovoice serve: ready: http://127.0.0.1:") and line.rstrip().endswith(f"({len(SIM_TOOLS)} tools)")
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
    import subprocess

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
