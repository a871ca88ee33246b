#!/usr/bin/env bash
# Configures and builds voxgi (and its tests) into build/. Warnings are errors under CI.
set -euo pipefail
cd "$(dirname "$0")/.."
werror=OFF
if [ "${CI:-}" = "true" ] || [ "${VOXGI_WERROR:-}" = "ON" ]; then werror=ON; fi
cmake -S . -B build -DCMAKE_BUILD_TYPE="${VOXGI_BUILD_TYPE:-Release}" -DVOXGI_WERROR="$werror" \
  -DVOXGI_SANITIZE="${VOXGI_SANITIZE:-OFF}" > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j"$(nproc)"
