#!/usr/bin/env bash
# Configures and builds voxgi (and its tests) into build/ (or VOXGI_BUILD_DIR). Warnings are
# errors under CI. Extra arguments go to CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${VOXGI_BUILD_DIR:-build}"
werror=OFF
if [ "${CI:-}" = "true" ] || [ "${VOXGI_WERROR:-}" = "ON" ]; then werror=ON; fi
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE="${VOXGI_BUILD_TYPE:-Release}" -DVOXGI_WERROR="$werror" \
  -DVOXGI_SANITIZE="${VOXGI_SANITIZE:-OFF}" "$@" > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build "$dir" -j"$(nproc)"
