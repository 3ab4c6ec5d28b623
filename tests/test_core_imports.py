"""The core package works with no extra installed: every core module imports, the CLI helps.

A child interpreter makes the extras' packages unimportable (a meta-path finder that refuses
them, as if they were not installed), imports every module of `robovoice`, and runs
``robovoice --help`` and each command's ``--help``. Modules that belong to an extra may fail
there, but only by saying which package is missing.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from typing import Any

import pytest

#: What the extras install (top-level import names), all made unimportable in the child.
EXTRA_PACKAGES = (
    "numpy", "zenoh", "llama_cpp", "onnxruntime", "faster_whisper", "ctranslate2", "piper", "sounddevice",
    "soundfile", "soxr", "rclpy", "openwakeword", "moonshine", "silero_vad",
)

#: Module name prefixes that belong to an extra (voice: audio and the voice pipeline; zenoh; ros2).
EXTRA_MODULES = (
    "robovoice.audio.", "robovoice.voice.", "robovoice.middleware.zenoh", "robovoice.middleware.bench_zenoh",
    "robovoice.middleware.ros2", "robovoice.middleware.bench_ros2", "robovoice.soak",
)

CHILD = textwrap.dedent("""
    import contextlib, importlib, importlib.abc, io, json, pkgutil, sys

    BLOCKED = set(sys.argv[1].split(","))

    class NotInstalled(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in BLOCKED:
                raise ModuleNotFoundError(f"No module named {name!r}", name=name)
            return None

    sys.meta_path.insert(0, NotInstalled())
    for name in list(sys.modules):  # nothing of them may have been imported before the finder
        if name.split(".")[0] in BLOCKED:
            del sys.modules[name]

    import robovoice
    from robovoice.cli import main

    modules = {}
    for info in pkgutil.walk_packages(robovoice.__path__, "robovoice."):
        try:
            importlib.import_module(info.name)
            modules[info.name] = None
        except Exception as exc:
            modules[info.name] = f"{type(exc).__name__}: {exc}"

    def help_of(*args):
        out = io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):
            try:
                main([*args, "--help"])
            except Exception as exc:
                return f"{type(exc).__name__}: {exc}"
        return out.getvalue()

    top = help_of()
    commands = [line.split()[0] for line in top.split("COMMAND")[-1].splitlines()[1:]
                if line.startswith("    ") and not line.startswith("     ")]
    helps = {command: help_of(command) for command in commands}
    loaded = sorted(name for name in sys.modules if name.split(".")[0] in BLOCKED)
    print(json.dumps({"modules": modules, "top": top, "helps": helps, "loaded": loaded}))
""")


@pytest.fixture(scope="module")
def report() -> dict[str, Any]:
    done = subprocess.run([sys.executable, "-c", CHILD, ",".join(EXTRA_PACKAGES)], capture_output=True, text=True,
                          timeout=120, check=False)
    assert done.returncode == 0, done.stderr
    result: dict[str, Any] = json.loads(done.stdout.splitlines()[-1])
    return result


def test_every_core_module_imports_without_extras(report: dict[str, Any]) -> None:
    modules: dict[str, str | None] = report["modules"]
    assert len(modules) > 50  # the walk found the package
    core_failures = {name: error for name, error in modules.items()
                     if error is not None and not name.startswith(EXTRA_MODULES)}
    assert core_failures == {}
    assert report["loaded"] == []


def test_extra_modules_fail_only_by_naming_what_is_missing(report: dict[str, Any]) -> None:
    modules: dict[str, str | None] = report["modules"]
    for name, error in modules.items():
        if error is None:
            continue
        assert name.startswith(EXTRA_MODULES)
        missing = error.startswith("ModuleNotFoundError") and any(f"'{p}" in error for p in EXTRA_PACKAGES)
        named_extra = error.startswith("MissingDependencyError") and "pip install 'robovoice[" in error
        assert missing or named_extra, f"{name}: {error}"


def test_the_cli_and_every_command_give_help_without_extras(report: dict[str, Any]) -> None:
    assert report["top"].startswith("usage: robovoice")
    helps: dict[str, str] = report["helps"]
    assert {"serve", "tools", "chat", "sim", "demo", "assist", "eval", "bench"} <= set(helps)
    for command, text in helps.items():
        assert text.startswith(f"usage: robovoice {command}"), f"robovoice {command} --help: {text[:300]}"
