#!/usr/bin/env bash
# Builds the input parsers with clang, AddressSanitizer and UndefinedBehaviorSanitizer and runs
# each libFuzzer target (tests/fuzz/) for SECONDS (default 60) from its committed seed corpus.
# The corpus grows in out/fuzz/<target>/; a finding (crash, sanitizer report, leak, input over
# 2 GiB of memory or FUZZ_TIMEOUT s) is written to out/fuzz/findings/ and makes the script fail.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: scene_json mesh exr vdb)
# The mutation seed is fixed (FUZZ_SEED, default 1), so a run explores the same inputs in the
# same order and two runs differ only in how far they get: CI stays reproducible. One input
# over FUZZ_TIMEOUT seconds (default 30; ASan makes assimp ~10x slower) is a finding.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_json mesh exr vdb)

start=$(date +%s)
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DVOXGI_FUZZ=ON \
  -DVOXGI_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build build-fuzz -j"$(nproc)" > out-fuzz-build.log 2>&1 || { tail -30 out-fuzz-build.log; exit 1; }
rm -f out-fuzz-build.log
echo "fuzz: build took $(( $(date +%s) - start )) s"

mkdir -p out/fuzz/findings
status=0
for t in "${targets[@]}"; do
  mkdir -p "out/fuzz/$t"
  log="out/fuzz/$t.log"
  # Leaks are not findings here: OpenVDB and assimp keep process-lifetime registries.
  if ASAN_OPTIONS=detect_leaks=0 "./build-fuzz/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -rss_limit_mb=2048 \
      -seed="${FUZZ_SEED:-1}" -timeout="${FUZZ_TIMEOUT:-30}" -print_final_stats=1 -artifact_prefix="out/fuzz/findings/$t-" \
      "out/fuzz/$t" "tests/fuzz/corpus/$t" > "$log" 2>&1; then
    result=ok
  else
    result="FINDING (see $log and out/fuzz/findings/)"
    status=1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  per=$(( runs / (seconds > 0 ? seconds : 1) ))
  echo "fuzz_$t: ${runs} inputs in ${seconds} s (~${per}/s), corpus $(ls "out/fuzz/$t" | wc -l) files: $result"
done
exit $status
