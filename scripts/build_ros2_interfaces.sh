#!/usr/bin/env bash
# Build and install robovoice's ROS 2 interface packages into a virtualenv with the pip-installed
# ROS 2 generators (no ROS install):
#   interfaces/robovoice_msgs                  JSON calls and actions of robovoice nodes hosted on
#                                              ROS 2 (robovoice sim --middleware ros2://…)
#   examples/ros2_robot/interfaces/nav2_msgs   only NavigateToPose, with Nav2's fields and type name,
#                                              for the example robot and the sim's /navigate_to_pose
#                                              (a robot with Nav2 has the real one)
# Each is skipped when it is importable already.
#   scripts/build_ros2_interfaces.sh [VENV]        (default .venv)
# Needs cmake, a C/C++ compiler and the Python headers (Debian: cmake g++ python3-dev).
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=$(cd "${1:-.venv}" && pwd)
PY=$VENV/bin/python
generator=Ninja; command -v ninja >/dev/null 2>&1 || generator="Unix Makefiles"

build() {  # build NAME SOURCE_DIR IMPORT
    local name=$1 src=$2 module=$3
    if "$PY" -c "import $module" >/dev/null 2>&1; then
        echo "[ros2] $name is already installed"; return 0
    fi
    "$PY" -m pip install -q -e '.[ros2-build]'
    local dir; dir=$(mktemp -d)
    echo "[ros2] building $name into $VENV (about a minute)"
    if ! (export PATH=$VENV/bin:$PATH AMENT_PREFIX_PATH=$VENV   # build time only
          cmake -S "$src" -B "$dir" -G "$generator" -DCMAKE_PREFIX_PATH="$VENV" -DCMAKE_INSTALL_PREFIX="$VENV" \
                -DPython3_EXECUTABLE="$PY" -DBUILD_TESTING=OFF >"$dir/log" 2>&1 \
          && cmake --build "$dir" -j"$(nproc)" >>"$dir/log" 2>&1 \
          && cmake --install "$dir" >>"$dir/log" 2>&1); then
        tail -30 "$dir/log" >&2; rm -rf "$dir"; echo "[ros2] building $name failed" >&2; return 1
    fi
    rm -rf "$dir"
    "$PY" -c "import $module" && echo "[ros2] $name installed"
}

build robovoice_msgs interfaces/robovoice_msgs robovoice_msgs.srv
build nav2_msgs examples/ros2_robot/interfaces/nav2_msgs nav2_msgs.action
