#!/usr/bin/env bash
# Times the open issues' GPU goals in one run on a machine with an NVIDIA GPU (the device tool
# lends one to some sessions, 15 minutes in all): prepare here, run there, read the logs back.
#
#   scripts/gpu-goals.sh pack                 here: .gpu/ (ignored by git) with a bundle of the
#                                             built voxgi (scripts/bundle.sh) and the shared scenes
#   scripts/gpu-goals.sh run OUT [--quick]    there (device run, carry [".gpu"], OUT="$OUT"): one
#                                             log per issue under OUT (six files), each step under
#                                             its own time limit so one slow step costs only itself
#
# The machine there has the driver but no Debian packages, and ../shared does not travel: `run`
# unpacks both from .gpu/ (the scenes beside the checkout, where scenes/*.json look for them).
# Without .gpu/ it runs build/tools/voxgi with the scenes it finds. --quick: small sizes and few
# frames, to check the script itself on llvmpipe. The goals each log answers:
#   ddgi.txt    issue 18: a 16x8x12 probe update <= 1 ms, >= 1 G probe-rays/s (trace = volume and bvh)
#   clpv.txt    issue 17: Sponza's CLPV update at 3x32^3 <= 2 ms, 3x64^3 <= 4 ms; Sibenik's
#               injection and blockers < 2 ms; and lpv.apply with lpv.tap_visibility=rays and
#               =cells (their cost is why they are off by default, docs/lpv.md)
#   isr.txt     issue 22: ISR at 1080p <= 1 ms, without and with the guard band
#   sky.txt     issue 19: sky apply <= 0.5 ms at 1080p
#   hybrid.txt  issue 20: the hybrid frame against clpv's
set -uo pipefail
cd "$(dirname "$0")/.."

pack() {
  set -e
  [ -x build/tools/voxgi ] || { echo "gpu-goals.sh: build first (scripts/build.sh)" >&2; exit 2; }
  [ -d ../shared/scenes ] || { echo "gpu-goals.sh: ../shared/scenes not found" >&2; exit 2; }
  mkdir -p .gpu
  scripts/bundle.sh -o .gpu/voxgi.tar.xz
  tar -C ../shared -cJf .gpu/scenes.tar.xz.partial scenes/crytek-sponza scenes/sibenik
  mv .gpu/scenes.tar.xz.partial .gpu/scenes.tar.xz
  local bytes
  bytes=$(du -cb .gpu/voxgi.tar.xz .gpu/scenes.tar.xz | tail -1 | cut -f1)
  echo "gpu-goals.sh: .gpu/ holds $((bytes / 1048576)) MiB (the device tool carries at most 64 MiB in all)"
  [ "$bytes" -lt $((60 * 1048576)) ] || { echo "gpu-goals.sh: too large to carry" >&2; exit 1; }
}

run() {
  local out="$1" quick="${2:-}"
  [ -n "$out" ] || { echo "gpu-goals.sh: run OUT [--quick]" >&2; exit 2; }
  mkdir -p "$out"
  local voxgi=build/tools/voxgi
  if [ -f .gpu/voxgi.tar.xz ]; then
    rm -rf /tmp/gpu-goals && mkdir -p /tmp/gpu-goals && tar -C /tmp/gpu-goals -xJf .gpu/voxgi.tar.xz
    voxgi=/tmp/gpu-goals/voxgi/voxgi
  fi
  if [ ! -d ../shared/scenes ] && [ -f .gpu/scenes.tar.xz ]; then
    mkdir -p ../shared && tar -C ../shared -xJf .gpu/scenes.tar.xz
  fi
  local size=1920x1080 frames=(--frames 10 --warmup 3) limit=150
  local scenes=(cornell-box scenes/sibenik.json scenes/sponza.json) probes=16,8,12
  if [ "$quick" = "--quick" ]; then
    size=64x64 frames=(--frames 2 --warmup 1) limit=300 scenes=(cornell-box) probes=4,4,4
  fi
  # One step: its command line, then its output, into the issue's log; never stops the run.
  step() {
    local log="$out/$1"
    shift
    echo "\$ voxgi $*" >>"$log"
    local start=$SECONDS
    timeout "$limit" "$voxgi" "$@" >>"$log" 2>&1
    echo "(exit $?, $((SECONDS - start)) s)" >>"$log"
    echo >>"$log"
  }
  { nvidia-smi -L 2>&1 || true; date -u; } >"$out/device.txt"
  step ddgi.txt bench ddgi "${scenes[@]}" "${frames[@]}" --set ddgi.probes="$probes"
  for r in 32 64; do
    step clpv.txt bench clpv "${scenes[@]}" --sizes "$size" --variants gl "${frames[@]}" --set lpv.resolution=$r
  done
  for taps in rays cells; do
    step clpv.txt bench clpv "${scenes[@]}" --sizes "$size" --variants gl "${frames[@]}" --set lpv.tap_visibility=$taps
  done
  for band in 0 0.125 0.25; do
    step isr.txt bench isr "${scenes[@]}" --sizes "$size" "${frames[@]}" --set isr.guard_band=$band
  done
  local noon=scenes/sponza-noon.json
  [ "$quick" = "--quick" ] && noon=scenes/outdoor.json
  step sky.txt bench direct "$noon" --sizes "$size" "${frames[@]}"
  step hybrid.txt bench hybrid scenes/cornell-spheres.json --sizes "$size" "${frames[@]}"
  step hybrid.txt bench clpv scenes/cornell-spheres.json --sizes "$size" --variants gl "${frames[@]}"
  grep -h "exit" "$out"/*.txt | sort | uniq -c
}

case "${1:-}" in
  pack) pack ;;
  run) shift; run "${1:-}" "${2:-}" ;;
  *) echo "usage: scripts/gpu-goals.sh pack | run OUT [--quick]" >&2; exit 2 ;;
esac
