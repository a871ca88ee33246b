#!/usr/bin/env bash
# Regenerates docs/results/: `voxgi eval` on the built-in Cornell box and, when ../shared/scenes
# is present, Sibenik and Sponza (every built method x low/medium/high against a path-traced
# reference), plus the stability suite. Path-traced references are cached outside the docs
# (VOXGI_EVAL_CACHE, default out/eval-cache) so a re-run only re-renders the real-time methods.
# Uses ./build/tools/voxgi unless VOXGI is set. See docs/eval.md.
set -euo pipefail
cd "$(dirname "$0")/.."
voxgi="${VOXGI:-./build/tools/voxgi}"
cache="${VOXGI_EVAL_CACHE:-out/eval-cache}"
methods="${VOXGI_EVAL_METHODS:-direct,ambient,lpv,clpv,ddgi}"
export EGL_PLATFORM="${EGL_PLATFORM:-surfaceless}"
[ -x "$voxgi" ] || { echo "make-results: $voxgi not found; run ./scripts/build.sh first" >&2; exit 1; }
mkdir -p "$cache"
start=$(date +%s)

out=docs/results
rm -rf "$out"
mkdir -p "$out"

# Cornell: 256^2, 1024 spp reference, 32 frames (the area light is sampled once per frame).
"$voxgi" eval cornell-box --methods "$methods" --presets low,medium,high --width 256 --height 256 \
  --spp 1024 --frames 32 --cache "$cache" -o "$out/cornell-box"

# The big scenes at 128^2 (llvmpipe on 2 cores), when their meshes are beside the checkout.
for scene in sibenik sponza; do
  mesh=$(grep -o '"path": *"[^"]*"' "scenes/$scene.json" | head -1 | sed 's/.*"\(.*\)"$/\1/')
  if [ -f "scenes/$mesh" ]; then
    "$voxgi" eval "scenes/$scene.json" --methods "$methods" --presets low,medium,high --width 128 --height 128 \
      --spp 512 --frames 9 --cache "$cache" -o "$out/$scene"
  else
    echo "make-results: skipping $scene (its mesh under ../shared/scenes is absent)"
  fi
done

# The stability table; a failing case is a finding to read, not a reason to stop.
"$voxgi" eval --stability -o "$out/stability" || echo "make-results: some stability cases failed (see stability.md)"

elapsed=$(( $(date +%s) - start ))
echo "make-results: wrote $out in ${elapsed} s"
