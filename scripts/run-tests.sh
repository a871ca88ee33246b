#!/usr/bin/env bash
# Set up, build and run the whole test suite through CTest (viewer tests get an Xvfb display).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
export EGL_PLATFORM=surfaceless
cd build
if [ -z "${DISPLAY:-}" ] && command -v xvfb-run > /dev/null; then
  xvfb-run -a -s "-screen 0 1280x1024x24" ctest --output-on-failure -j"$(nproc)" --timeout 900
else
  ctest --output-on-failure -j"$(nproc)" --timeout 900
fi
