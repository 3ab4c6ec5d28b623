"""No test skips because something is not installed: in CI such a skip hides a missing install
step. A test that needs a package or program fails instead, naming the install step
(`tests/conftest.py`, `tests/installed.py`). A skip that is about the machine itself (it has
sound devices, say) stays, and says so on its line or the line above: "not a missing install"."""

from __future__ import annotations

import re
from pathlib import Path

TESTS = Path(__file__).resolve().parent
SKIP = re.compile(r"importorskip|pytest\.skip\(|mark\.skipif|mark\.skip\(")
ALLOWED = "not a missing install"


def test_no_test_skips_for_a_missing_install() -> None:
    offending = []
    for path in sorted(TESTS.rglob("*.py")):
        if path == Path(__file__).resolve():
            continue
        lines = path.read_text(encoding="utf-8").splitlines()
        for number, line in enumerate(lines, 1):
            above = lines[number - 2] if number > 1 else ""
            if SKIP.search(line) and ALLOWED not in line and ALLOWED not in above:
                offending.append(f"{path.relative_to(TESTS.parent)}:{number}: {line.strip()}")
    assert offending == [], "use tests/installed.py's require()/missing() or a fixture of tests/conftest.py:\n" + \
        "\n".join(offending)
