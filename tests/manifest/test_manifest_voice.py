"""A manifest tool's `voice` section: roles, phrase templates (checked when the manifest is
read, filled safely when spoken), and what `robovoice check-manifests` says about the roles."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from robovoice.errors import ManifestError
from robovoice.manifest import check_manifest_dir, validate_manifest
from robovoice.manifest.check import NO_STOP_TOOL, UNCHECKED_FIT
from robovoice.manifest.errors import ManifestErrors
from robovoice.manifest.voice import fill, template_fields


def _write(path: Path, data: dict[str, Any]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data), encoding="utf-8")


def _errors(data: dict[str, Any]) -> list[ManifestError]:
    with pytest.raises(ManifestErrors) as caught:
        validate_manifest(data, "nav.json")
    return list(caught.value.errors)


def test_a_voice_section_with_role_and_phrases_is_read(nav: dict[str, Any]) -> None:
    nav["tools"][0]["voice"] = {"role": "motion", "say": {"start": "On my way to the {target}.",
                                                          "progress": "Still on my way, {message}."}}
    nav["snapshots"][0]["voice"] = {"role": "pose"}
    manifest = validate_manifest(nav, "nav.json")
    voice = manifest.tools[0].voice
    assert voice is not None and voice.role == "motion" and voice.say.start == "On my way to the {target}."
    assert voice.meta() == {"role": "motion", "say": {"start": "On my way to the {target}.",
                                                      "progress": "Still on my way, {message}."}}
    assert manifest.snapshots[0].voice is not None and manifest.snapshots[0].voice.role == "pose"
    assert manifest.tools[1].voice is None


@pytest.mark.parametrize(("where", "voice", "says"), [
    ("tools", {"role": "dance"}, "role"),
    ("tools", {"role": "pose"}, "pose role belongs to a snapshot"),
    ("snapshots", {"role": "stop"}, "can only be pose"),
    ("tools", {"say": {"start": "On my way to the {target.name}."}}, "not a plain field name"),
    ("tools", {"say": {"start": "Going {}."}}, "not a plain field name"),
    ("tools", {"say": {"start": "Going to the {target"}}, "start"),
    ("tools", {"say": {"finish": "Done."}}, "finish"),
])  # fmt: skip
def test_bad_voice_sections_are_refused_at_their_path(
    nav: dict[str, Any], where: str, voice: dict[str, Any], says: str
) -> None:
    nav[where][0]["voice"] = voice
    errors = _errors(nav)
    assert any(f"$.{where}[0].voice" in e.path and says in str(e) for e in errors), errors


@pytest.mark.parametrize(("template", "fields", "said"), [
    ("On my way to the {target}.", {"target": "kitchen"}, "On my way to the kitchen."),
    ("On my way to the {target}.", {}, None),  # a missing field: nothing is said, nothing raises
    ("On my way to the {target}.", {"target": None}, None),
    ("{percent:.0f} percent done.", {"percent": 42.4}, "42 percent done."),
    ("{percent:.0f} percent done.", {"percent": "most"}, None),  # the value does not fit its spec
    ("Battery at {percent}%.", {"percent": 80, "other": 1}, "Battery at 80%."),
    ("{message!r}", {"message": "x"}, "'x'"),
    ("", {}, None),
    (None, {}, None),
])  # fmt: skip
def test_phrases_are_filled_safely(template: str | None, fields: dict[str, Any], said: str | None) -> None:
    assert fill(template, fields) == said


def test_template_fields() -> None:
    assert template_fields("From {start} to {target:>10}.") == ["start", "target"]
    with pytest.raises(ValueError, match="plain field"):
        template_fields("{0}")
    with pytest.raises(ValueError, match="nested"):
        template_fields("{x:{width}}")


def test_check_manifests_says_when_no_tool_has_the_stop_role(tmp_path: Path, nav: dict[str, Any]) -> None:
    _write(tmp_path / "navigation" / "mcp.json", nav)
    report = check_manifest_dir(tmp_path)
    assert report.ok and NO_STOP_TOOL in report.notes
    assert f"note: {NO_STOP_TOOL}" in report.lines()
    _write(tmp_path / "base" / "mcp.json", {"node": "base", "tools": [
        {"name": "emergency_stop", "rpc": "stop", "description": "Stop now.", "voice": {"role": "stop"}}]})
    assert NO_STOP_TOOL not in check_manifest_dir(tmp_path).notes


def test_check_manifests_names_the_actuation_tools_without_words(tmp_path: Path) -> None:
    _write(tmp_path / "base" / "mcp.json", {"node": "base", "tools": [
        {"name": "emergency_stop", "rpc": "stop", "description": "Stop now.",
         "voice": {"role": "stop", "words": ["stop", "halt"]}},
        {"name": "open_gripper", "rpc": "open", "description": "Open the gripper."},
        {"name": "get_status", "rpc": "status", "description": "Status.", "annotations": {"readOnlyHint": True}}]})
    notes = check_manifest_dir(tmp_path).notes
    assert f"{UNCHECKED_FIT} open_gripper" in notes  # neither the stop (it has words) nor the look-up


def test_the_sims_manifests_declare_their_roles() -> None:
    import robovoice.sim

    report = check_manifest_dir(Path(robovoice.sim.__file__).parent / "manifests")
    assert report.ok and report.notes == ()
