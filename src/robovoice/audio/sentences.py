"""Streaming sentence splitter: LLM text deltas in, sentences for TTS out.

`SentenceSplitter.feed(delta)` returns the sentences completed so far; `flush()` returns the
rest at the end of the reply. A sentence ends at ``.``, ``!``, ``?`` (with any closing
quotes/brackets) followed by whitespace and the start of a new sentence, or at a line break
followed by a new paragraph, list item or capitalised line. It never ends inside numbers
("3.5 metres", "1,000"), after abbreviations and titles ("Dr. Weber", "e.g.", "approx."),
after initials ("J. Smith"), or at an ellipsis. When a sentence grows past `max_chars`
without ending, it is cut at a clause break (comma, semicolon, colon, dash) so speech can
start early; past `hard_max_chars` at a space.

Because "Dr." or "3." may continue, a sentence is released only once the next non-space
character has arrived (or at `flush`). Pure code, no models.
"""

from __future__ import annotations

import re
from typing import Final

_TERMINATORS: Final = ".!?\u2026"
_CLOSERS: Final = "\"')]}\u00bb\u201d\u2019"
_OPENERS: Final = "\"'([{\u00ab\u201c\u2018"
_BULLETS: Final = "-*\u2022#>"

#: Abbreviations after which a period never ends a sentence (compared lower-case, without
#: the final period).
NEVER_FINAL: Final = frozenset(
    {
        "dr", "mr", "mrs", "ms", "mx", "prof", "st", "sr", "jr", "rev", "gen", "col", "capt", "lt", "sgt",
        "hon", "fr", "e.g", "i.e", "eg", "ie", "approx", "appr", "ca", "cf", "vs", "viz", "fig", "figs",
        "vol", "dept", "mt", "ave", "blvd", "tel", "ext", "z.b", "d.h", "bzw", "usw",
    }
)  # fmt: skip
#: Abbreviations that may end a sentence: they do when a capital letter follows.
MAYBE_FINAL: Final = frozenset({"etc", "a.m", "p.m", "u.s", "u.k", "e.u"})

_CLAUSE_BREAK: Final = re.compile(r"[,;:](?=\s)|\s[\u2013\u2014-](?=\s)")


class SentenceSplitter:
    """Splits streamed text into sentences (see the module docstring for the rules)."""

    def __init__(self, *, max_chars: int = 120, min_clause_chars: int = 24, hard_max_chars: int = 250) -> None:
        if not 0 < min_clause_chars < max_chars <= hard_max_chars:
            raise ValueError("need 0 < min_clause_chars < max_chars <= hard_max_chars")
        self.max_chars = max_chars
        self.min_clause_chars = min_clause_chars
        self.hard_max_chars = hard_max_chars
        self._buf = ""

    @property
    def pending(self) -> str:
        """Text received but not yet returned."""
        return self._buf

    def reset(self) -> None:
        """Drop pending text (e.g. on barge-in)."""
        self._buf = ""

    def feed(self, delta: str) -> list[str]:
        """Add a text delta; return the sentences it completed (possibly none)."""
        self._buf += delta
        out: list[str] = []
        while True:
            cut = _find_boundary(self._buf)
            if cut is None:
                cut = self._long_clause_cut()
            if cut is None:
                break
            sentence, self._buf = self._buf[:cut].strip(), self._buf[cut:].lstrip()
            if sentence:
                out.append(sentence)
        return out

    def flush(self) -> str | None:
        """End of the text: the remaining sentence, or None when nothing is left."""
        rest, self._buf = self._buf.strip(), ""
        return rest or None

    def _long_clause_cut(self) -> int | None:
        buf = self._buf
        text_len = len(buf.rstrip())
        if text_len <= self.max_chars:
            return None
        best: int | None = None
        for m in _CLAUSE_BREAK.finditer(buf, self.min_clause_chars):
            end = m.end()
            if end > self.max_chars and best is not None:
                break
            if not buf[end:].strip():  # need text after the break to be sure it is one
                break
            best = end
        if best is not None:
            return best
        if text_len > self.hard_max_chars:
            space = buf.rfind(" ", self.min_clause_chars, self.hard_max_chars)
            return space if space > 0 else self.hard_max_chars
        return None


def _word_before(buf: str, i: int) -> str:
    """The non-space token that ends just before index `i`."""
    start = i
    while start > 0 and not buf[start - 1].isspace():
        start -= 1
    return buf[start:i].lstrip(_OPENERS)


def _starts_line(buf: str, i: int, word: str) -> bool:
    start = i - len(word)
    before = buf[:start].rstrip(" \t")
    return before == "" or before.endswith("\n")


def _starts_sentence(ch: str) -> bool:
    return ch.isupper() or ch.isdigit() or ch in _OPENERS


def _find_boundary(buf: str) -> int | None:
    """Index just past the end of the first complete sentence in `buf`, or None when there
    is none yet (or the first candidate still needs more text to be decided)."""
    n = len(buf)
    i = 0
    while i < n:
        ch = buf[i]
        if ch == "\n":
            k = i
            while k < n and buf[k].isspace():
                k += 1
            if k == n:
                return None  # cannot tell yet what follows the line break
            nxt = buf[k]
            if ("\n" in buf[i + 1 : k] or _starts_sentence(nxt) or nxt in _BULLETS) and buf[:i].strip():
                return i
            i = k
            continue
        if ch not in _TERMINATORS:
            i += 1
            continue
        # a run of terminators, then closing quotes/brackets
        j = i
        while j < n and buf[j] in _TERMINATORS:
            j += 1
        run = buf[i:j]
        while j < n and buf[j] in _CLOSERS:
            j += 1
        if j == n:
            return None  # "3." may become "3.5", "Dr." may be followed by a name
        if not buf[j].isspace():
            i = j  # "3.5", "e.g.,", "U.S.A", "Hello.World": not an end
            continue
        k = j
        while k < n and buf[k].isspace():
            k += 1
        if k == n:
            return None
        nxt = buf[k]
        new_line = "\n" in buf[j:k]
        if _is_sentence_end(buf, i, run, nxt) or (new_line and _line_may_end(buf, i, run)):
            return j
        i = k
    return None


def _line_may_end(buf: str, i: int, run: str) -> bool:
    """At a line break almost any terminator ends the sentence, but not a list number."""
    if run != ".":
        return True
    word = _word_before(buf, i)
    return not (word.isdigit() and _starts_line(buf, i, word))


def _is_sentence_end(buf: str, i: int, run: str, nxt: str) -> bool:
    if "\u2026" in run or ".." in run:
        return False  # ellipsis: a pause, not an end
    if "!" in run or "?" in run:
        return True
    word = _word_before(buf, i)
    low = word.lower()
    if low in NEVER_FINAL:
        return False
    if low in MAYBE_FINAL:
        return nxt.isupper()
    if low == "no" and nxt.isdigit():
        return False  # "No. 5"
    if len(word) == 1 and word.isalpha() and word.isupper():
        return False  # an initial: "J. Smith"
    if "." in word:
        return False  # other dotted abbreviations: "p.h.d.", "a.k.a."
    if word.isdigit() and _starts_line(buf, i, word):
        return False  # a numbered list item: "1. Go to the kitchen"
    return _starts_sentence(nxt)
