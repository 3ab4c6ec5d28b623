"""Helpers for multi-process tests on loopback: free ports, child processes that are
always reaped, bounded waits. Every child gets a fresh port; multicast scouting is off
(the adapter's default), so tests never see each other's processes."""

from __future__ import annotations

import asyncio
import os
import queue
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BOUND_S = 10.0


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


class Child:
    """A child process whose output lines are collected by a thread."""

    def __init__(self, name: str, argv: list[str], env: dict[str, str] | None = None) -> None:
        self.name = name
        self.argv = argv
        env = dict(os.environ if env is None else env, PYTHONUNBUFFERED="1")
        self.proc = subprocess.Popen(argv, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True, start_new_session=True)
        self.lines: list[str] = []
        self._queue: queue.Queue[str | None] = queue.Queue()
        self._reader = threading.Thread(target=self._read, name=f"read-{name}", daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.append(line.rstrip("\n"))
            self._queue.put(line.rstrip("\n"))
        self._queue.put(None)

    def wait_for_line(self, needle: str, bound: float = BOUND_S) -> str:
        """Block until a line containing `needle` is printed; fail (with the output) otherwise."""
        deadline = time.monotonic() + bound
        while (left := deadline - time.monotonic()) > 0:
            try:
                line = self._queue.get(timeout=left)
            except queue.Empty:
                break
            if line is None:
                pytest.fail(f"{self.name} exited ({self.proc.wait()}) before printing {needle!r}:\n"
                            + self.output())
            if needle in line:
                return line
        pytest.fail(f"{self.name} did not print {needle!r} within {bound} s:\n" + self.output())

    async def async_wait_for_line(self, needle: str, bound: float = BOUND_S) -> str:
        return await asyncio.to_thread(self.wait_for_line, needle, bound)

    def output(self) -> str:
        return "\n".join(self.lines[-60:])

    def kill(self) -> None:
        """SIGKILL, as a crash would."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
        self.proc.wait(5)
        self._reader.join(2)
        if self.proc.stdout is not None and not self._reader.is_alive():
            self.proc.stdout.close()  # no ResourceWarning (pytest -W error)

    def stop(self, bound: float = 5.0) -> int:
        """SIGTERM, then SIGKILL if it does not exit within `bound` seconds; the exit status."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(bound)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait(5)
        self._reader.join(2)
        if self.proc.stdout is not None and not self._reader.is_alive():
            self.proc.stdout.close()  # no ResourceWarning (pytest -W error)
        return self.proc.returncode


def robovoice(*args: str) -> list[str]:
    return [sys.executable, "-m", "robovoice.cli", *args]


def sim_argv(uri: str, *nodes: str, speed: float = 1.0) -> list[str]:
    args = ["sim", "--middleware", uri, "--speed", str(speed)]
    for node in nodes:
        args += ["--node", node]
    return robovoice(*args)
