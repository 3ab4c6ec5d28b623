"""Every module in src has one job and stays readable: at most 400 lines (DESIGN.md §3, issue 9)."""

from __future__ import annotations

from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "robovoice"
MAX_LINES = 400


def test_no_module_is_over_400_lines() -> None:
    modules = sorted(SRC.rglob("*.py"))
    assert len(modules) > 50
    too_long = {str(path.relative_to(SRC)): n for path in modules
                if (n := len(path.read_text(encoding="utf-8").splitlines())) > MAX_LINES}
    assert too_long == {}, "split these by job: " + ", ".join(f"{p} ({n} lines)" for p, n in too_long.items())
