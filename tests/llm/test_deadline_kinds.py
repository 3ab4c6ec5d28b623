"""Deadlines that fit the backend: defaults by kind (local CPU server, edge GPU server, cloud),
overridable per backend in the config file; a chain fails over at once when a server cannot be
reached, but lets a reachable one think as long as its own deadline allows."""

from __future__ import annotations

import argparse
import dataclasses
import time
from pathlib import Path

import pytest

from robovoice.commands.common import add_llm_args, backend_from_args
from robovoice.config import BackendConfig, kind_for_url, load_config
from robovoice.errors import ConfigError
from robovoice.llm.base import DEADLINES_BY_KIND, ChatMessage, Deadlines, TextDelta, ToolSpec
from robovoice.llm.failover import AllBackendsFailedError, FailoverBackend
from robovoice.llm.fake_server import FakeOpenAIServer, Pacing, TextReply
from robovoice.llm.openai_compat import OpenAICompatBackend

USER = [ChatMessage("user", "How much battery do you have?")]


@pytest.mark.parametrize(("url", "kind"), [
    ("http://127.0.0.1:8088/v1", "local-cpu"), ("http://localhost:8080/v1", "local-cpu"),
    ("http://[::1]:8000/v1", "local-cpu"), ("http://edge:8000/v1", "edge-gpu"),
    ("http://192.168.1.20:8000/v1", "edge-gpu"), ("https://api.example.com/v1", "cloud"),
])
def test_the_kind_follows_from_the_url_when_not_given(url: str, kind: str) -> None:
    assert kind_for_url(url) == kind
    backend = BackendConfig(url=url, model="m")
    assert backend.kind == kind and backend.deadlines() == DEADLINES_BY_KIND[backend.kind]


def test_defaults_by_kind_give_a_cpu_server_time_to_read_its_prompt() -> None:
    cpu, gpu, cloud = (DEADLINES_BY_KIND[k] for k in ("local-cpu", "edge-gpu", "cloud"))
    assert (cpu.first_token_s, gpu.first_token_s, cloud.first_token_s) == (60.0, 10.0, 15.0)
    for d in (cpu, gpu, cloud):
        assert d.connect_s < d.first_token_s <= d.total_s  # unreachable is known long before thinking ends


def test_a_kind_and_single_deadlines_come_from_the_config_file(tmp_path: Path) -> None:
    path = tmp_path / "robovoice.toml"
    path.write_text('[[llm.backends]]\nurl = "http://gpu-box:8000/v1"\nmodel = "m"\nkind = "local-cpu"\n'
                    'first_token_s = 90\n\n[[llm.backends]]\nurl = "https://api.example.com/v1"\nmodel = "m"\n'
                    'connect_s = 1.5\n')
    cpu, cloud = load_config(path).llm.backends
    assert cpu.deadlines() == Deadlines(connect_s=2.0, first_token_s=90.0, idle_s=20.0, total_s=120.0)
    assert cloud.kind == "cloud"
    assert cloud.deadlines() == Deadlines(connect_s=1.5, first_token_s=15.0, idle_s=15.0, total_s=60.0)


def test_a_server_on_this_machine_named_on_the_command_line_gets_a_cpu_servers_patience() -> None:
    """The issue's case: `--llm http://127.0.0.1:8088/v1` gave up after 8 s while the server read its prompt."""
    parser = argparse.ArgumentParser()
    add_llm_args(parser)
    chain = backend_from_args(parser.parse_args(["--llm", "http://127.0.0.1:8088/v1", "--model", "qwen"]))
    server = chain.backends[0]
    assert isinstance(server, OpenAICompatBackend)
    cpu = DEADLINES_BY_KIND["local-cpu"]
    assert (server.deadlines.connect_s, server.deadlines.first_token_s) == (cpu.connect_s, cpu.first_token_s)


def test_the_embedded_model_takes_its_first_token_deadline_from_the_config(tmp_path: Path) -> None:
    from robovoice.llm.base import LOCAL_DEADLINES
    from robovoice.llm.local import LocalLlamaBackend

    path = tmp_path / "robovoice.toml"
    path.write_text("[[llm.backends]]\nlocal = true\nfirst_token_s = 90\n")
    parser = argparse.ArgumentParser()
    add_llm_args(parser)
    chain = backend_from_args(parser.parse_args([]), load_config(path))
    local = chain.backends[0]
    assert isinstance(local, LocalLlamaBackend)
    assert local.deadlines == dataclasses.replace(LOCAL_DEADLINES, first_token_s=90.0)
    path.write_text("[[llm.backends]]\nlocal = true\n")
    unchanged = backend_from_args(parser.parse_args([]), load_config(path)).backends[0]
    assert isinstance(unchanged, LocalLlamaBackend) and unchanged.deadlines == LOCAL_DEADLINES
    path.write_text("[[llm.backends]]\nlocal = true\nconnect_s = 1\n")
    with pytest.raises(ConfigError, match="connect_s: for url backends only"):
        load_config(path)


def test_a_bad_kind_names_the_field_and_the_accepted_kinds(tmp_path: Path) -> None:
    path = tmp_path / "robovoice.toml"
    path.write_text('[[llm.backends]]\nurl = "http://edge:8000/v1"\nmodel = "m"\nkind = "gpu"\n')
    with pytest.raises(ConfigError, match=r"robovoice.toml: llm\.backends\.0\.kind: Input should be 'local-cpu', "
                                          r"'edge-gpu' or 'cloud' \(got 'gpu'\)"):
        load_config(path)
    path.write_text('[[llm.backends]]\nlocal = true\nkind = "cloud"\n')
    with pytest.raises(ConfigError, match="kind: for url backends only"):
        load_config(path)


async def test_a_refused_connection_fails_over_at_once_despite_a_long_first_token_deadline(
    unused_port: int, tools: list[ToolSpec]
) -> None:
    patient = DEADLINES_BY_KIND["local-cpu"]  # would wait 60 s for a first token
    async with FakeOpenAIServer([TextReply("Eighty percent.")]) as edge:
        dead = OpenAICompatBackend(f"http://127.0.0.1:{unused_port}/v1", "m", name="dead", deadlines=patient)
        alive = OpenAICompatBackend(edge.base_url, edge.model, name="edge", deadlines=DEADLINES_BY_KIND["edge-gpu"])
        chain = FailoverBackend([dead, alive])
        try:
            start = time.monotonic()
            text = "".join([e.text async for e in chain.stream(USER, tools) if isinstance(e, TextDelta)])
            elapsed = time.monotonic() - start
        finally:
            await chain.aclose()
    assert text == "Eighty percent."
    assert elapsed < 3.0, f"failing over took {elapsed:.1f} s"
    dead_health = next(h for h in chain.health() if h.name == "dead")
    assert not dead_health.healthy and "cannot reach" in (dead_health.last_error or "")


async def test_a_thinking_server_is_waited_for_past_the_chains_own_safety_net(tools: list[ToolSpec]) -> None:
    """The chain's first-event bound never cuts a backend shorter than its own deadlines."""
    async with FakeOpenAIServer([TextReply("Eighty percent.", pacing=Pacing(first_token_delay_s=2.0))]) as cpu:
        thinking = OpenAICompatBackend(cpu.base_url, cpu.model, name="cpu",
                                       deadlines=Deadlines(connect_s=1.0, first_token_s=5.0))
        chain = FailoverBackend([thinking], first_event_timeout_s=0.5)
        try:
            text = "".join([e.text async for e in chain.stream(USER, tools) if isinstance(e, TextDelta)])
        finally:
            await chain.aclose()
    assert text == "Eighty percent." and all(h.healthy for h in chain.health())


async def test_a_server_thinking_past_its_deadline_is_reported_by_that_deadline(tools: list[ToolSpec]) -> None:
    async with FakeOpenAIServer([TextReply("Too late.", pacing=Pacing(first_token_delay_s=3.0))]) as slow:
        backend = OpenAICompatBackend(slow.base_url, slow.model, name="slow",
                                      deadlines=Deadlines(connect_s=1.0, first_token_s=0.5))
        chain = FailoverBackend([backend])
        try:
            with pytest.raises(AllBackendsFailedError, match=r"slow: first_token deadline of 0\.5 s exceeded"):
                async for _ in chain.stream(USER, tools):
                    pass
        finally:
            await chain.aclose()
