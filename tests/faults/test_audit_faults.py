"""The disk for the audit log fails under a running robot: tool calls still answer, the
failure is logged once and counted, and the log picks up again when the disk comes back."""

from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest

from robovoice.address import SimAddress
from robovoice.mcp_server import open_robot_side
from robovoice.mcp_server.audit import read_audit
from robovoice.mcp_server.embedded import open_embedded_client


async def test_a_full_disk_never_fails_a_tool_call(caplog: pytest.LogCaptureFixture) -> None:
    async with (open_robot_side(SimAddress(speed=50), manifests=None, audit_log=Path("/dev/full")) as side,
                open_embedded_client(side, snapshot_warmup_s=0.5) as client):
        for _ in range(3):
            result = await client.call_tool("get_battery_state", {})
            assert not result.is_error
        moved = await client.call_tool("navigate_to", {"target": "kitchen"})
        assert not moved.is_error
        assert side.server.audit.failures == 4 and side.server.audit.written == 0
    errors = [r for r in caplog.records if r.levelname == "ERROR" and "audit log" in r.getMessage()]
    assert len(errors) == 1 and "No space left on device" in errors[0].getMessage()


async def test_a_read_only_disk_mid_run_then_back(tmp_path: Path, caplog: pytest.LogCaptureFixture,
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "audit.jsonl"
    async with (open_robot_side(SimAddress(speed=50), manifests=None, audit_log=path) as side,
                open_embedded_client(side, snapshot_warmup_s=0.5) as client):
        assert not (await client.call_tool("get_battery_state", {})).is_error
        real_write = os.write

        def read_only(fd: int, data: bytes) -> int:
            raise OSError(errno.EROFS, os.strerror(errno.EROFS))

        monkeypatch.setattr(os, "write", read_only)  # the file system was remounted read-only
        try:
            assert not (await client.call_tool("get_robot_pose", {})).is_error
            assert not (await client.call_tool("list_contacts", {})).is_error
        finally:
            monkeypatch.setattr(os, "write", real_write)
        assert not (await client.call_tool("get_projector_state", {})).is_error
        assert side.server.audit.failures == 2
    tools = [r["tool"] for r in read_audit(path).records]
    assert tools == ["get_battery_state", "get_projector_state"]  # the failed two are counted, not torn
    assert read_audit(path).skipped == []
    assert sum("Read-only file system" in r.getMessage() for r in caplog.records) == 1
    assert any("being written again" in r.getMessage() for r in caplog.records)
