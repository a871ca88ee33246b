#!/usr/bin/env bash
# Regenerates docs/results/: `voxgi eval` on the built-in Cornell box and, when ../shared/scenes
# is present, Sibenik, Sponza and Sponza under the atmosphere (every built method x
# low/medium/high against a path-traced reference), plus the stability suite. Path-traced references are cached outside the docs
# (VOXGI_EVAL_CACHE, default out/eval-cache) so a re-run only re-renders the real-time methods.
# Uses ./build/tools/voxgi unless VOXGI is set. See docs/eval.md.
set -euo pipefail
cd "$(dirname "$0")/.."
voxgi="${VOXGI:-./build/tools/voxgi}"
cache="${VOXGI_EVAL_CACHE:-out/eval-cache}"
# Every built method unless VOXGI_EVAL_METHODS lists some (comma-separated).
methods=()
if [ -n "${VOXGI_EVAL_METHODS:-}" ]; then methods=(--methods "$VOXGI_EVAL_METHODS"); fi
export EGL_PLATFORM="${EGL_PLATFORM:-surfaceless}"
[ -x "$voxgi" ] || { echo "make-results: $voxgi not found; run ./scripts/build.sh first" >&2; exit 1; }
mkdir -p "$cache"
start=$(date +%s)

out=docs/results
rm -rf "$out"
mkdir -p "$out"

# The Cornell box at 256^2 (1024 spp reference, 8 warm-up + 32 frames: its area light is sampled
# once per frame) in docs/results/, then Sibenik, Sponza and Sponza at noon under the atmosphere,
# when their meshes are beside the checkout, in one report at 128^2 (llvmpipe on 2 cores) with
# 512 spp and 4 warm-up + 8 frames in docs/results/large-scenes/.
"$voxgi" eval cornell-box "${methods[@]}" --presets low,medium,high --width 256 --height 256 \
  --spp 1024 --frames 40 --warmup 8 --cache "$cache" -o "$out"
big=()
# sponza-noon is Sponza under the atmosphere (it extends sponza.json, whose mesh it needs).
for scene in sibenik sponza sponza-noon; do
  file="scenes/$scene.json"
  base=$(grep -m1 -o '"extends": *"[^"]*"' "$file" | sed 's/.*"\(.*\)"$/\1/' || true)
  [ -n "$base" ] && file="scenes/$base"
  mesh=$(grep -m1 -o '"path": *"[^"]*"' "$file" | sed 's/.*"\(.*\)"$/\1/')
  if [ -f "scenes/$mesh" ]; then
    big+=("scenes/$scene.json")
  else
    echo "make-results: skipping $scene (its mesh under ../shared/scenes is absent)"
  fi
done
if [ ${#big[@]} -gt 0 ]; then
  "$voxgi" eval "${big[@]}" "${methods[@]}" --presets low,medium,high --width 128 --height 128 \
    --spp 512 --frames 12 --warmup 4 --cache "$cache" -o "$out/large-scenes"
fi

# Mirrors and glass (docs/hybrid.md): the spheres' Cornell box, the hybrid method against the
# diffuse methods alone (128^2, 4096 spp: the glass's caustics are noisy in the reference).
"$voxgi" eval scenes/cornell-spheres.json --methods direct,clpv,ddgi,hybrid --presets medium --width 128 --height 128 \
  --spp 4096 --cache "$cache" -o "$out/hybrid"
# The same against a reference without caustics (docs/hybrid.md): what the methods aim at, since
# none carries light to a diffuse surface through the spheres.
"$voxgi" eval scenes/cornell-spheres.json --methods direct,clpv,ddgi,hybrid --presets medium --width 128 --height 128 \
  --spp 4096 --no-caustics --cache "$cache" -o "$out/hybrid-no-caustics"

# Seed 003's protocol (docs/eval.md "many views"): the Cornell box, Sibenik and Sponza (when
# their meshes are present) over 100 camera views each, drawn in the free space their own camera
# stands in, each view against its own reference (64^2, 256 spp): direct light, the ambient
# (fitted, and held out) and ISR (views/). Then the Cornell box's views with LPV, CLPV and DDGI
# at their medium presets (views-methods/, three frames a view; DDGI settles at the first view
# and keeps its field, about 20 min in all), Sibenik's and Sponza's with the same methods
# (views-methods-sibenik/ and views-methods-sponza/, about 20 and 40 min), and the Cornell box's
# with CLPV and ISR with CLPV as its far field (views-far-field/).
views_scenes=(cornell-box)
for scene in "${big[@]}"; do
  case "$scene" in *sibenik.json | *sponza.json) views_scenes+=("$scene") ;; esac
done
views_methods=(--methods "${VOXGI_EVAL_METHODS:-direct,ambient,isr}")
"$voxgi" eval "${views_scenes[@]}" "${views_methods[@]}" --views 100 --presets medium --width 64 --height 64 \
  --spp 256 --frames 6 --warmup 2 --cache "$cache" -o "$out/views"
"$voxgi" eval cornell-box --methods "${VOXGI_EVAL_METHODS:-direct,ambient,lpv,clpv,ddgi}" --views 100 \
  --presets medium --width 64 --height 64 --spp 256 --frames 3 --warmup 1 --cache "$cache" -o "$out/views-methods"
for scene in "${big[@]}"; do
  case "$scene" in
    *sibenik.json | *sponza.json)
      name=$(basename "$scene" .json)
      "$voxgi" eval "$scene" --methods "${VOXGI_EVAL_METHODS:-direct,ambient,lpv,clpv,ddgi}" --views 100 --presets medium \
        --width 64 --height 64 --spp 256 --frames 3 --warmup 1 --cache "$cache" -o "$out/views-methods-$name" ;;
  esac
done
"$voxgi" eval cornell-box --methods direct,clpv,isr --views 100 --presets medium --width 64 --height 64 --spp 256 \
  --frames 6 --warmup 2 --cache "$cache" -o "$out/views-far-field" --set isr.far_field=clpv --set lpv.resolution=32 \
  --set lpv.steps=fit --set lpv.cascades=3 --set lpv.reuse=false
# ISR with a guard band of a quarter of the picture beyond each edge (docs/isr.md "Guard band";
# the default is an eighth): direct light and ISR over the same 100 views of each scene.
"$voxgi" eval "${views_scenes[@]}" --methods direct,isr --views 100 --presets medium --width 64 --height 64 \
  --spp 256 --frames 6 --warmup 2 --cache "$cache" -o "$out/views-guard-band" --set isr.guard_band=0.25

# The stability table; a failing case is a finding to read, not a reason to stop.
"$voxgi" eval --stability -o "$out/stability" || echo "make-results: some stability cases failed (see stability.md)"

elapsed=$(( $(date +%s) - start ))
{
  echo "# voxgi results"
  echo
  echo "Generated by \`./scripts/make-results.sh\` in ${elapsed} s on $(nproc) cores ($(date -u +%Y-%m-%d)); see [docs/eval.md](../eval.md)."
  echo
  echo "- [Cornell box: error against time, all methods and presets](report.md)"
  if [ ${#big[@]} -gt 0 ]; then
    echo "- [Sibenik, Sponza, and Sponza at noon under the atmosphere](large-scenes/report.md)"
  else
    echo "- Sibenik and Sponza: not run (../shared/scenes absent)"
  fi
  echo "- [Mirrors and glass: the spheres' Cornell box with the hybrid method](hybrid/report.md)"
  echo "- [The same against a reference without caustics (what the methods aim at)](hybrid-no-caustics/report.md)"
  echo "- [Cornell box, Sibenik and Sponza over 100 views each (direct light, ambient, ISR): spread, share of views beating direct light and the fitted ambient, worst views](views/views.md)"
  echo "- [Cornell box over the same 100 views: LPV, CLPV and DDGI (medium)](views-methods/views.md)"
  [ -d "$out/views-methods-sibenik" ] && echo "- [Sibenik over the same 100 views: LPV, CLPV and DDGI (medium)](views-methods-sibenik/views.md)"
  [ -d "$out/views-methods-sponza" ] && echo "- [Sponza over the same 100 views: LPV, CLPV and DDGI (medium)](views-methods-sponza/views.md)"
  echo "- [Cornell box over 100 views: CLPV, and ISR with CLPV as its far field](views-far-field/views.md)"
  echo "- [Cornell box, Sibenik and Sponza over the same 100 views: ISR with a guard band of 0.25 against direct light](views-guard-band/views.md)"
  echo "- [Stability suite](stability/stability.md)"
} > "$out/README.md"
echo "make-results: wrote $out in ${elapsed} s"
