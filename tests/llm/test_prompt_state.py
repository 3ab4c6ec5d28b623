"""The warmed-up prefix kept on disk (llm/prompt_state.py), with the real embedded model: a
second start loads it instead of evaluating it and answers exactly as the first; a state that
does not load, or that was made for other words, is evaluated as before. A short prompt keeps
each evaluation to a second or two."""

from __future__ import annotations

from pathlib import Path

import pytest

from robovoice.llm.base import ChatMessage, Deadlines, TextDelta
from robovoice.llm.local import LocalLlamaBackend
from robovoice.llm.model_store import resolve_model_path
from robovoice.llm.prompt_state import FOLDER

pytestmark = [pytest.mark.integration, pytest.mark.usefixtures("local_model_installed")]

PROMPT = "You are a helpful robot in a flat. Answer in one short sentence."
PATIENT = Deadlines(first_token_s=120, idle_s=60, total_s=300)


async def _start(cache: Path, prompt: str = PROMPT) -> tuple[LocalLlamaBackend, bool, str]:
    """A fresh backend warmed up with `prompt`: it, whether the state came from disk, and its answer."""
    backend = LocalLlamaBackend(resolve_model_path(), cache_dir=cache, tool_bias=0.0, deadlines=PATIENT)
    stats = await backend.warm_up(prompt, [])
    messages = [ChatMessage("system", prompt), ChatMessage("user", "Which room do people cook in?")]
    answer = "".join([e.text async for e in backend.stream(messages, []) if isinstance(e, TextDelta)])
    assert backend.last_turn.cached_prompt_tokens >= stats.prompt_tokens  # the turn started from the prefix
    return backend, stats.from_disk, answer


async def test_a_second_start_loads_the_prefix_and_answers_the_same(tmp_path: Path) -> None:
    first, from_disk, answer = await _start(tmp_path)
    await first.aclose()
    [state] = (tmp_path / FOLDER).glob("*.state")
    assert not from_disk and state.stat().st_size > 0
    second, from_disk, again = await _start(tmp_path)
    await second.aclose()
    assert from_disk and again == answer and answer.strip()


async def test_a_state_that_does_not_load_or_is_for_other_words_is_evaluated(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    first, _, answer = await _start(tmp_path)
    await first.aclose()
    [state] = (tmp_path / FOLDER).glob("*.state")
    state.write_bytes(state.read_bytes()[:1000])  # cut short, as by a full disk
    second, from_disk, again = await _start(tmp_path)
    await second.aclose()
    assert not from_disk and again == answer and "does not load" in caplog.text
    other, from_disk, _ = await _start(tmp_path, PROMPT + " Be kind.")  # another prompt: another state
    await other.aclose()
    assert not from_disk and len(list((tmp_path / FOLDER).glob("*.state"))) == 2
