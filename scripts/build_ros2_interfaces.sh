#!/usr/bin/env bash
# Build and install robovoice's ROS 2 interface package(s) into a virtualenv with the
# pip-installed ROS 2 generators (no ROS install): today nav2_msgs with only NavigateToPose,
# the fields and type name of Nav2's, for the example robot (examples/ros2_robot) and tests.
# Skipped when nav2_msgs is already importable (a robot with the real Nav2 has it).
#   scripts/build_ros2_interfaces.sh [VENV]        (default .venv)
# Needs cmake, a C/C++ compiler and the Python headers (Debian: cmake g++ libpython3-dev).
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=$(cd "${1:-.venv}" && pwd)
PY=$VENV/bin/python
if "$PY" -c "import nav2_msgs.action" >/dev/null 2>&1; then
    echo "[ros2] nav2_msgs is already installed"; exit 0
fi
"$PY" -m pip install -q -e '.[ros2-build]'
generator=Ninja; command -v ninja >/dev/null 2>&1 || generator="Unix Makefiles"
build=$(mktemp -d)
trap 'rm -rf "$build"' EXIT
export PATH=$VENV/bin:$PATH AMENT_PREFIX_PATH=$VENV      # build time only
echo "[ros2] building nav2_msgs (NavigateToPose) into $VENV (about a minute)"
cmake -S examples/ros2_robot/interfaces/nav2_msgs -B "$build" -G "$generator" -DCMAKE_PREFIX_PATH="$VENV" \
      -DCMAKE_INSTALL_PREFIX="$VENV" -DPython3_EXECUTABLE="$PY" -DBUILD_TESTING=OFF >"$build/log" 2>&1 \
    && cmake --build "$build" -j"$(nproc)" >>"$build/log" 2>&1 \
    && cmake --install "$build" >>"$build/log" 2>&1 \
    || { tail -30 "$build/log" >&2; echo "[ros2] building nav2_msgs failed" >&2; exit 1; }
"$PY" -c "from nav2_msgs.action import NavigateToPose" && echo "[ros2] nav2_msgs installed"
