#!/usr/bin/env bash
# Install everything (scripts/setup.sh), run the official MCP conformance scenarios against
# `robovoice serve --robot sim --transport http`, then the whole test suite (last, so that its
# summary line closes the output).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/conformance.sh
.venv/bin/python -m pytest -q "$@"
