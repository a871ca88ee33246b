#!/usr/bin/env bash
# The main job: set up, build, render the built-in Cornell box to out/cornell.exr + .png.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
mkdir -p out
export EGL_PLATFORM=surfaceless
./build/tools/voxgi render cornell-box --method "${VOXGI_METHOD:-direct}" \
  -o out/cornell.exr --png out/cornell.png --timings out/cornell-timings.json
