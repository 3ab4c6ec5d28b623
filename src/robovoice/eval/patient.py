"""``python -m robovoice.eval.patient eval FILE …``: robovoice's command line with the embedded
model's deadlines raised so far that none fires. For accuracy figures, never for latency.

Accuracy does not depend on the machine's load, but the embedded model's first-token deadline
(`llm.base.LOCAL_DEADLINES`, 30 s) does: on a loaded 2-core machine the model misses it, the
turn says "I can't reach my language model" and does nothing, and doing nothing passes every
no-action case. A config file can raise a `local` backend's `first_token_s` (docs/llm.md); this
entry point raises the idle and total bounds too, with no file to write. The report's
`model_unanswered` says whether a deadline still fired.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from robovoice.llm import registry
from robovoice.llm.base import Deadlines

PATIENT_DEADLINES = Deadlines(connect_s=0.0, first_token_s=900.0, idle_s=300.0, total_s=1800.0)


def main(argv: Sequence[str] | None = None) -> int:
    setattr(registry, "LOCAL_DEADLINES", PATIENT_DEADLINES)  # noqa: B010 - read when the local backend is built
    from robovoice.cli import main as cli_main

    return cli_main(argv)


if __name__ == "__main__":
    sys.exit(main())
