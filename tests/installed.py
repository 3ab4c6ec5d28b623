"""A test needs something installed: fail, naming the install step (a skip would hide it in CI)."""

from __future__ import annotations

from typing import NoReturn

import pytest

SETUP = "run `bash scripts/setup.sh`"


def missing(what: str, install: str) -> NoReturn:
    """Fail (not skip) the calling test: `what` is not installed; `install` says how to get it."""
    pytest.fail(f"{what} is not installed: {SETUP} ({install})", pytrace=False)


def require(ok: bool, what: str, install: str) -> None:
    """`missing(what, install)` unless `ok`."""
    if not ok:
        missing(what, install)
