#!/usr/bin/env bash
# Run the official MCP conformance scenarios that apply to robovoice's server (tools, no
# resources, no prompts) against `robovoice serve --robot sim --transport http` on a free
# loopback port. Exits non-zero when any scenario fails or the server does not come up.
#
#   bash scripts/conformance.sh            # the applicable scenarios (see docs/mcp-server.md)
#   bash scripts/conformance.sh ping       # only the scenarios named
#
# The suite (@modelcontextprotocol/conformance, pinned below; 0.1.13 is the last release that
# runs on Node 20) is installed once into .cache/conformance (git-ignored).
set -euo pipefail
cd "$(dirname "$0")/.."

CONFORMANCE_VERSION=0.1.13
PREFIX=.cache/conformance
SUITE="$PREFIX/node_modules/@modelcontextprotocol/conformance/dist/index.js"
ROBOVOICE=${ROBOVOICE:-.venv/bin/robovoice}
SCENARIOS=(server-initialize ping tools-list dns-rebinding-protection server-sse-multiple-streams)
[ $# -gt 0 ] && SCENARIOS=("$@")

say() { printf '\033[1m[conformance]\033[0m %s\n' "$*"; }
die() { printf '\033[1m[conformance]\033[0m error: %s\n' "$*" >&2; exit 1; }

command -v node >/dev/null 2>&1 || die "node is not installed (apt-get install nodejs npm)"
[ -x "$ROBOVOICE" ] || die "$ROBOVOICE not found: run scripts/setup.sh first"

# --- the suite, pinned -----------------------------------------------------------------------
installed=$(node -p "require('./$PREFIX/node_modules/@modelcontextprotocol/conformance/package.json').version" \
    2>/dev/null || true)
if [ "$installed" != "$CONFORMANCE_VERSION" ]; then
    say "installing @modelcontextprotocol/conformance@$CONFORMANCE_VERSION into $PREFIX"
    mkdir -p "$PREFIX"
    npm install --silent --no-save --no-audit --no-fund --prefix "$PREFIX" \
        "@modelcontextprotocol/conformance@$CONFORMANCE_VERSION" >/dev/null
fi
[ -f "$SUITE" ] || die "the conformance suite did not install ($SUITE missing)"

# --- the server under test -------------------------------------------------------------------
workdir=$(mktemp -d)
server_pid=""
cleanup() {
    if [ -n "$server_pid" ] && kill -0 "$server_pid" 2>/dev/null; then
        kill -TERM "$server_pid" 2>/dev/null || true
        for _ in $(seq 50); do kill -0 "$server_pid" 2>/dev/null || break; sleep 0.1; done
        kill -KILL "$server_pid" 2>/dev/null || true
    fi
    rm -rf "$workdir"
}
trap cleanup EXIT

"$ROBOVOICE" serve --robot sim --transport http --port 0 --no-audit-log \
    >"$workdir/stdout" 2>"$workdir/stderr" &
server_pid=$!

url=""
for _ in $(seq 300); do  # up to 30 s for the "ready" line
    url=$(grep -o 'ready: http://[^ ]*' "$workdir/stdout" 2>/dev/null | cut -d' ' -f2 || true)
    [ -n "$url" ] && break
    kill -0 "$server_pid" 2>/dev/null || { cat "$workdir/stderr" >&2; die "the server exited during start-up"; }
    sleep 0.1
done
[ -n "$url" ] || { cat "$workdir/stderr" >&2; die "the server did not report ready within 30 s"; }
say "server under test: $url"

# --- the scenarios ----------------------------------------------------------------------------
failed=()
for scenario in "${SCENARIOS[@]}"; do
    if node "$SUITE" server --url "$url" --scenario "$scenario" >"$workdir/$scenario.log" 2>&1; then
        say "PASS $scenario ($(grep -o 'Passed: [0-9/]*' "$workdir/$scenario.log" | tail -1))"
    else
        say "FAIL $scenario"
        sed 's/^/    /' "$workdir/$scenario.log" >&2
        failed+=("$scenario")
    fi
done

if [ ${#failed[@]} -gt 0 ]; then
    die "${#failed[@]} of ${#SCENARIOS[@]} scenarios failed: ${failed[*]}"
fi
say "all ${#SCENARIOS[@]} scenarios passed"
