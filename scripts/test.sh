#!/usr/bin/env bash
# Install everything (scripts/setup.sh), lint and type-check src and tests (ruff, mypy --strict),
# run the official MCP conformance scenarios against `robovoice serve --robot sim --transport http`,
# then the whole test suite with warnings as errors (pyproject.toml: filterwarnings) -- last, so that
# its summary line closes the output.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
echo "[test] ruff check src tests"
.venv/bin/ruff check src tests
echo "[test] mypy --strict src tests"
.venv/bin/mypy --strict src tests
bash scripts/conformance.sh
.venv/bin/python -m pytest -q "$@"
