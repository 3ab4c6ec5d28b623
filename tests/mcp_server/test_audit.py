"""The audit log under stress: kill -9 while writing, rotation by size (several processes),
a read-only directory, a full disk, a file size limit, torn lines, and `robovoice audit`."""

from __future__ import annotations

import errno
import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from robovoice.cli import main
from robovoice.mcp_server.audit import AuditLog, AuditRecord, audit_files, read_audit, rotated_path

WRITER = textwrap.dedent("""
    import sys, threading
    from pathlib import Path
    from robovoice.mcp_server.audit import AuditLog, AuditRecord

    path, name, max_bytes, keep = Path(sys.argv[1]), sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    log = AuditLog(path, max_bytes=max_bytes, keep=keep)
    counts = [0, 0, 0]

    def write(thread: int) -> None:
        while True:
            counts[thread] += 1
            log.record(AuditRecord(started=1.0, session=name, client=str(thread), tool="t", node=None, rpc=None,
                                   arguments={"n": counts[thread], "pad": "x" * 3000}, outcome="ok", result=None,
                                   error=None, duration_ms=0.1))
            if thread == 0 and counts[0] % 100 == 0:
                print(counts[0], flush=True)

    for i in range(1, 3):
        threading.Thread(target=write, args=(i,), daemon=True).start()
    write(0)
""")


def _record(tool: str = "t", **arguments: object) -> AuditRecord:
    return AuditRecord(started=1_795_000_000.0, session=None, client=None, tool=tool, node="n", rpc="r",
                       arguments=dict(arguments), outcome="ok", result={"ok": True}, error=None, duration_ms=1.0)


def _writer(path: Path, name: str, max_bytes: int = 0, keep: int = 5) -> subprocess.Popen[str]:
    return subprocess.Popen([sys.executable, "-c", WRITER, str(path), name, str(max_bytes), str(keep)],
                            stdout=subprocess.PIPE, text=True)


def _kill_after(proc: subprocess.Popen[str], hundreds: int) -> None:
    assert proc.stdout is not None
    for _ in range(hundreds):
        assert proc.stdout.readline(), "the writer died"
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    proc.stdout.close()


def _parse_all_but_last(path: Path) -> list[dict[str, object]]:
    lines = path.read_bytes().split(b"\n")
    body, last = lines[:-1], lines[-1]  # `last` is b"" when the file ends with a newline
    records = [json.loads(line) for line in body]  # every complete line parses
    if last:
        with pytest.raises(ValueError):
            json.loads(last)
    return records


def test_kill_9_while_three_threads_write_leaves_at_most_a_torn_last_line(tmp_path: Path) -> None:
    path = tmp_path / "audit.jsonl"
    writer = _writer(path, "a")
    _kill_after(writer, 5)
    records = _parse_all_but_last(path)
    assert len(records) >= 500
    reading = read_audit(path)
    assert len(reading.records) == len(records)
    assert all(s.torn for s in reading.skipped) and len(reading.skipped) <= 1
    # a new writer ends any torn line first: its records never merge into the remains
    with path.open("ab") as f:
        f.write(b'{"tool": "half')
    log = AuditLog(path)
    log.record(_record("after"))
    log.close()
    reading = read_audit(path)
    assert reading.records[-1]["tool"] == "after"
    assert [s.torn for s in reading.skipped][-1] is False  # the old torn line is now a damaged one


def test_a_peer_rotating_while_we_open_adds_no_empty_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # A peer rotates between our open and the torn-line check, and its fresh file is shorter and
    # mid-record: the check must read the file we opened (it once wrote "\n" into the rotated one).
    path = tmp_path / "audit.jsonl"
    path.write_bytes(b'{"tool": "old"}\n' * 10)
    real_open = AuditLog._open

    def open_then_peer_rotates(target: Path) -> int:
        fd = real_open(target)
        os.replace(target, rotated_path(target, 1))
        target.write_bytes(b'{"to')  # the peer's fresh file, a record half written
        return fd

    monkeypatch.setattr(AuditLog, "_open", staticmethod(open_then_peer_rotates))
    AuditLog(path).close()
    assert rotated_path(path, 1).read_bytes() == b'{"tool": "old"}\n' * 10
    assert path.read_bytes() == b'{"to'


def test_two_processes_rotate_under_load_and_kill_9_loses_nothing_complete(tmp_path: Path) -> None:
    path = tmp_path / "audit.jsonl"
    writers = [_writer(path, name, max_bytes=60_000, keep=1000) for name in ("a", "b")]
    for writer in writers:
        _kill_after(writer, 3)
    # A writer killed between a rotation's rename and its reopen leaves no current file;
    # that loses nothing, so the current file is read only when it is there.
    files = audit_files(path)
    rotated = [file for file in files if file != path]
    assert len(rotated) > 5  # rotated many times
    for file in rotated:
        assert file.stat().st_size <= 60_000 + 4_000  # one line may tip a file just over when a peer rotated
    for file in files:
        _parse_all_but_last(file)
    reading = read_audit(path)
    # each writer thread's records are numbered 1, 2, 3…: none is missing before the kill
    seen: dict[tuple[object, object], list[int]] = {}
    for record in reading.records:
        arguments = record["arguments"]
        assert isinstance(arguments, dict)
        seen.setdefault((record["session"], record["client"]), []).append(int(arguments["n"]))
    assert len(seen) == 6
    for numbers in seen.values():
        assert sorted(numbers) == list(range(1, len(numbers) + 1))


def test_rotation_keeps_n_files(tmp_path: Path) -> None:
    path = tmp_path / "audit.jsonl"
    log = AuditLog(path, max_bytes=500, keep=3)
    for i in range(60):
        log.record(_record(n=i))
    log.close()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["audit.jsonl", "audit.jsonl.1", "audit.jsonl.2",
                                                          "audit.jsonl.3"]
    numbers = [r["arguments"]["n"] for r in read_audit(path).records]
    assert numbers == list(range(numbers[0], 60)) and numbers[0] > 0  # newest kept, in order
    assert [r["arguments"]["n"] for r in read_audit(path, rotated=False).records][-1] == 59
    assert rotated_path(path, 2).stat().st_size <= 500


def _refuse_renames(monkeypatch: pytest.MonkeyPatch) -> None:
    def read_only(*_: object, **__: object) -> None:
        raise OSError(errno.EROFS, os.strerror(errno.EROFS))

    monkeypatch.setattr(os, "replace", read_only)


def test_a_read_only_directory_stops_rotation_not_the_calls(tmp_path: Path, caplog: pytest.LogCaptureFixture,
                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "audit.jsonl"
    log = AuditLog(path, max_bytes=300, keep=2)
    log.record(_record(n=0))
    if os.geteuid() == 0:  # root ignores directory permissions: the rename fails as on a read-only mount
        _refuse_renames(monkeypatch)
    tmp_path.chmod(0o500)
    try:
        for i in range(1, 6):
            log.record(_record(n=i))  # never raises
    finally:
        tmp_path.chmod(0o700)
        monkeypatch.undo()
    assert log.failures == 5 and log.written == 1
    assert sum("cannot append to the audit log" in r.message for r in caplog.records) == 1  # said once
    log.record(_record(n=6))
    assert log.written == 2 and "being written again" in caplog.text
    log.close()


def test_a_full_disk_is_counted_and_said_once(caplog: pytest.LogCaptureFixture) -> None:
    log = AuditLog(Path("/dev/full"), max_bytes=0)
    for i in range(4):
        log.record(_record(n=i))  # ENOSPC on every write; the call is not broken
    log.close()
    assert log.failures == 4 and log.written == 0
    errors = [r for r in caplog.records if r.levelname == "ERROR"]
    assert len(errors) == 1 and "No space left on device" in errors[0].getMessage()


def test_a_file_size_limit_mid_line_leaves_no_torn_line(tmp_path: Path) -> None:
    path = tmp_path / "audit.jsonl"
    script = textwrap.dedent("""
        import resource, signal, sys
        from pathlib import Path
        from robovoice.mcp_server.audit import AuditLog, AuditRecord
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)   # EFBIG / short write instead of the signal
        resource.setrlimit(resource.RLIMIT_FSIZE, (5000, 5000))
        log = AuditLog(Path(sys.argv[1]), max_bytes=0)
        for i in range(20):
            log.record(AuditRecord(started=1.0, session=None, client=None, tool="t", node=None, rpc=None,
                                   arguments={"n": i, "pad": "x" * 700}, outcome="ok", result=None, error=None,
                                   duration_ms=0.0))
        print(log.written, log.failures)
    """)
    done = subprocess.run([sys.executable, "-c", script, str(path)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    written, failures = map(int, done.stdout.split())
    assert written + failures == 20 and failures > 0 and written > 0
    assert done.stderr.count("cannot append to the audit log") == 1
    assert path.read_bytes().endswith(b"\n")  # the partial line was taken back
    assert [r["arguments"]["n"] for r in read_audit(path).records] == list(range(written))


def _write_log(path: Path) -> None:
    log = AuditLog(path)
    log.record(_record("navigate_to", target="kitchen"))
    log.record(AuditRecord(started=1_795_000_100.0, session=None, client=None, tool="navigate_to", node="n",
                           rpc="r", arguments={"target": "mars"}, outcome="error", result=None,
                           error={"error": "unknown_target", "message": "no mars", "hint": None, "details": {}},
                           duration_ms=3.0))
    log.record(_record("get_battery"))
    log.close()
    with path.open("ab") as f:
        f.write(b'{"time": "2026')  # killed mid-record


def test_robovoice_audit_filters_and_summarises(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "audit.jsonl"
    _write_log(path)
    assert main(["audit", str(path)]) == 0
    out, err = capsys.readouterr()
    assert len(out.splitlines()) == 3 and "ERROR unknown_target: no mars" in out
    assert "skipped an incomplete last line" in err and "audit.jsonl:4" in err
    assert main(["audit", str(path), "--errors", "--json"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [json.loads(line)["arguments"] for line in lines] == [{"target": "mars"}]
    assert main(["audit", str(path), "--tool", "get_battery", "--json"]) == 0
    assert [json.loads(line)["tool"] for line in capsys.readouterr().out.splitlines()] == ["get_battery"]
    assert main(["audit", str(path), "--since", "2026-11-18T11:08:00", "--json"]) == 0
    assert [json.loads(line)["outcome"] for line in capsys.readouterr().out.splitlines()] == ["error"]
    assert main(["audit", str(path), "--since", "1h"]) == 0
    assert capsys.readouterr().out == ""  # all older than an hour
    assert main(["audit", str(path), "--summary", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["calls"] == 3 and summary["errors"] == 1 and summary["skipped_lines"] == 1
    assert summary["tools"]["navigate_to"] == {"calls": 2, "errors": 1, "median_ms": 2.0, "p95_ms": 2.9}
    assert summary["error_codes"] == {"unknown_target": 1}
    assert main(["audit", str(path), "--summary"]) == 0
    assert "3 calls, 1 errors" in capsys.readouterr().out


def test_robovoice_audit_without_a_log_says_where_it_looked(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["audit", str(tmp_path / "none.jsonl")]) == 1
    assert "no audit log at" in capsys.readouterr().err


def test_serve_and_call_take_the_rotation_settings(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "audit.jsonl"
    for _ in range(4):
        assert main(["call", "--robot", "sim://?speed=50", "get_battery_state", "--audit-log", str(path),
                     "--audit-max-mb", "0.0002", "--audit-keep", "2"]) == 0  # ~210 bytes: one record a file
    capsys.readouterr()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["audit.jsonl", "audit.jsonl.1", "audit.jsonl.2"]
    assert [r["tool"] for r in read_audit(path).records] == ["get_battery_state"] * 3


def test_a_gap_in_the_rotated_numbers_hides_no_file(tmp_path: Path) -> None:
    """A writer killed between a rotation's renames (.2 moved to .3, .1 not yet to .2) leaves
    a gap; the older files past it are still read, oldest first."""
    path = tmp_path / "audit.jsonl"
    for n, name in ((3, "oldest"), (1, "older")):
        rotated_path(path, n).write_text(json.dumps({"tool": name}) + "\n")
    path.write_text(json.dumps({"tool": "newest"}) + "\n")
    (tmp_path / "audit.jsonl.bak").write_text("not a rotated file\n")
    assert [r["tool"] for r in read_audit(path).records] == ["oldest", "older", "newest"]
