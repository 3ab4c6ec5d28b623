#!/usr/bin/env bash
# Install everything (scripts/setup.sh, and llama.cpp's llama-server for the real-server tests:
# scripts/build_llama_server.sh, once per machine, built while the next steps run), lint and
# type-check src and tests (ruff, mypy --strict),
# run the official MCP conformance scenarios against `robovoice serve --robot sim --transport http`,
# then the whole test suite with warnings as errors (pyproject.toml: filterwarnings) -- last, so that
# its summary line closes the output.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# llama-server compiles (about 11 min on 2 cores the first time) beside the lint, the type check
# and the conformance scenarios, which leave a core free; the tests wait for it
build_log=$(mktemp)
bash scripts/build_llama_server.sh >"$build_log" 2>&1 &
build=$!
echo "[test] ruff check src tests"
.venv/bin/ruff check src tests
echo "[test] mypy --strict src tests"
.venv/bin/mypy --strict src tests
bash scripts/conformance.sh
echo "[test] waiting for llama-server's build"
wait "$build" || { cat "$build_log" >&2; echo "llama-server build failed" >&2; exit 1; }
rm -f "$build_log"
# pytest's summary closes the output: files that libraries keep open for their whole life
# (llama-cpp-python's two on /dev/null) may be reported after it as the interpreter exits, so
# the summary line is repeated last, and pytest's exit status is the script's.
log=$(mktemp)
set +e
.venv/bin/python -m pytest -q "$@" 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
set -e
grep -E '^[0-9]+ [a-z]+.* in [0-9.]+s' "$log" | tail -1 || true
rm -f "$log"
exit "$status"
