"""SentenceSplitter: pure text rules, fed whole and in every chunking."""

from __future__ import annotations

import subprocess
import sys

import pytest

from robovoice.audio.sentences import SentenceSplitter


def split(text: str, step: int | None = None, **kwargs: int) -> list[str]:
    splitter = SentenceSplitter(**kwargs)
    out: list[str] = []
    step = step or len(text) or 1
    for i in range(0, len(text), step):
        out.extend(splitter.feed(text[i : i + step]))
    rest = splitter.flush()
    if rest is not None:
        out.append(rest)
    return out


CASES: list[tuple[str, list[str]]] = [
    ("Hello there. How are you?", ["Hello there.", "How are you?"]),
    ("Stop! Now! Really?! Yes.", ["Stop!", "Now!", "Really?!", "Yes."]),
    ("I will drive 3.5 metres forward. Then I stop.", ["I will drive 3.5 metres forward.", "Then I stop."]),
    ("It costs 1,000 euros. That is a lot.", ["It costs 1,000 euros.", "That is a lot."]),
    ("Calling Dr. Weber now. Please wait.", ["Calling Dr. Weber now.", "Please wait."]),
    ("Mr. and Mrs. Smith are here. Ms. Lee too.", ["Mr. and Mrs. Smith are here.", "Ms. Lee too."]),
    (
        "Use a room, e.g. the kitchen. Or i.e. this one.",
        ["Use a room, e.g. the kitchen.", "Or i.e. this one."],
    ),
    ("It is approx. three metres away. Okay.", ["It is approx. three metres away.", "Okay."]),
    ("Well... I am not sure. Maybe.", ["Well... I am not sure.", "Maybe."]),
    ("Hmm\u2026 Let me think. Done.", ["Hmm\u2026 Let me think.", "Done."]),
    ('He said "Stop." Then he left.', ['He said "Stop."', "Then he left."]),
    ("(See the map.) Next one.", ["(See the map.)", "Next one."]),
    ("J. R. R. Tolkien wrote it. Nice.", ["J. R. R. Tolkien wrote it.", "Nice."]),
    (
        "Meet at 5 p.m. Then we go. It is 5 p.m. sharp.",
        ["Meet at 5 p.m.", "Then we go.", "It is 5 p.m. sharp."],
    ),
    ("Apples, pears, etc. Then more.", ["Apples, pears, etc.", "Then more."]),
    ("Room No. 5 is free. I said no. Then I left.", ["Room No. 5 is free.", "I said no.", "Then I left."]),
    ("the value is 3. 4 is next.", ["the value is 3.", "4 is next."]),
    ("version 2.0.1 is out. ok", ["version 2.0.1 is out. ok"]),
    ("Places:\n- kitchen\n- bedroom\n\nWhich one?", ["Places:", "- kitchen", "- bedroom", "Which one?"]),
    ("1. Go to the kitchen.\n2. Call Anna.", ["1. Go to the kitchen.", "2. Call Anna."]),
    ("First line\nSecond line", ["First line", "Second line"]),
    ("a hard-wrapped\nline of text.", ["a hard-wrapped\nline of text."]),
    ("Done.\nnext line starts lower case", ["Done.", "next line starts lower case"]),
    ("No terminator at the end", ["No terminator at the end"]),
    ("  Spaces around.   And more.  ", ["Spaces around.", "And more."]),
    ("", []),
]


@pytest.mark.parametrize(("text", "expected"), CASES)
def test_whole_text(text: str, expected: list[str]) -> None:
    assert split(text) == expected


@pytest.mark.parametrize(("text", "expected"), CASES)
@pytest.mark.parametrize("step", [1, 2, 3, 7])
def test_any_chunking_gives_the_same_sentences(text: str, expected: list[str], step: int) -> None:
    assert split(text, step) == expected


def test_sentence_released_as_soon_as_the_next_one_starts() -> None:
    s = SentenceSplitter()
    assert s.feed("I am on my way") == []
    assert s.feed(". ") == []  # "way. " might still be "way. e.g." -> wait for the next letter
    assert s.feed("T") == ["I am on my way."]
    assert s.pending == "T"


def test_ambiguous_endings_wait_for_more_text() -> None:
    s = SentenceSplitter()
    assert s.feed("Call Dr.") == []
    assert s.feed(" Weber") == []
    assert s.feed(" now. It") == ["Call Dr. Weber now."]
    s2 = SentenceSplitter()
    assert s2.feed("Drive 3.") == []
    assert s2.feed("5 metres! ") == []
    assert s2.feed("Ok") == ["Drive 3.5 metres!"]


def test_flush_returns_rest_once_and_none_when_empty() -> None:
    s = SentenceSplitter()
    s.feed("All done.")
    assert s.flush() == "All done."
    assert s.flush() is None
    s.feed("   ")
    assert s.flush() is None


def test_reset_drops_pending_text() -> None:
    s = SentenceSplitter()
    s.feed("This will be interrupted")
    s.reset()
    assert s.pending == ""
    assert s.flush() is None


def test_long_clause_is_cut_at_a_comma_so_speech_can_start_early() -> None:
    text = (
        "I can drive to the kitchen, the living room, the bedroom, the bathroom, the hallway, "
        "the front door and the charging dock, and I can also call Anna or Ben for you."
    )
    s = SentenceSplitter(max_chars=60, min_clause_chars=20)
    out: list[str] = []
    for ch in text:
        out.extend(s.feed(ch))
    rest = s.flush()
    assert rest is not None
    pieces = [*out, rest]
    assert len(pieces) >= 3
    assert " ".join(pieces) == text
    assert all(p.endswith(",") for p in out)
    assert all(len(p) <= 60 for p in out)


def test_commas_inside_numbers_are_not_clause_breaks() -> None:
    text = "The numbers are 1,000,000 and 2,500,000 and 3,750,000 and 4,125,000 and also 5,000,000 in total"
    assert split(text, 1, max_chars=40, min_clause_chars=10) == [text]


def test_very_long_run_without_punctuation_is_cut_at_a_space() -> None:
    words = " ".join(f"word{i}" for i in range(80))
    pieces = split(words, 5, max_chars=60, min_clause_chars=20, hard_max_chars=100)
    assert " ".join(pieces) == words
    assert len(pieces) > 1
    assert all(len(p) <= 100 for p in pieces)


def test_bad_limits_are_refused() -> None:
    with pytest.raises(ValueError, match="min_clause_chars"):
        SentenceSplitter(max_chars=10, min_clause_chars=20)


def test_sentences_module_imports_without_numpy() -> None:
    code = "import sys; sys.modules['numpy'] = None; import robovoice.audio.sentences as m; print(m.__name__)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "robovoice.audio.sentences"
