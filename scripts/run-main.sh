#!/usr/bin/env bash
# The main job: set up, build, render the built-in Cornell box with GI (the method its scene file
# names, or VOXGI_METHOD) to out/cornell.exr + .png, path-trace the reference once (cached in
# out/), print the error.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
mkdir -p out
export EGL_PLATFORM=surfaceless
voxgi=./build/tools/voxgi
method=()
if [ -n "${VOXGI_METHOD:-}" ]; then method=(--method "$VOXGI_METHOD"); fi
$voxgi render cornell-box "${method[@]}" --plan \
  -o out/cornell.exr --png out/cornell.png --timings out/cornell-timings.json
spp="${VOXGI_REFERENCE_SPP:-256}"
if [ ! -f "out/cornell-reference-${spp}spp.exr" ]; then
  $voxgi reference cornell-box --spp "$spp" -o "out/cornell-reference-${spp}spp.exr" \
    --png out/cornell-reference.png
fi
echo "error against the path-traced reference (${spp} spp):"
$voxgi compare out/cornell.exr "out/cornell-reference-${spp}spp.exr" --diff out/cornell-flip.png
echo "indirect light only:"
$voxgi compare out/cornell.exr "out/cornell-reference-${spp}spp.exr" --aov indirect
