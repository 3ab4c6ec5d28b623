#!/usr/bin/env bash
# Install everything (scripts/setup.sh) and run the whole test suite, then the official
# MCP conformance scenarios against `robovoice serve --robot sim --transport http`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/python -m pytest -q "$@"
bash scripts/conformance.sh
