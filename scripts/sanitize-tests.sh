#!/usr/bin/env bash
# The whole test suite against build-asan/, where the code that reads input and writes files
# (VOXGI_INPUT_DIRS in cmake/VoxgiOptions.cmake: scenes, volumes, tools, path tracer, ray tracer,
# metrics, sampling) runs under AddressSanitizer and UndefinedBehaviorSanitizer and the rest is
# built as usual (ccache serves it after scripts/build.sh). Any sanitizer report fails the test
# whose run made it. Leaks are not checked: Mesa, OpenVDB and assimp keep process-lifetime state.
# Usage: scripts/sanitize-tests.sh [CTEST_ARGS...]   (e.g. -R MeshFiles)
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
VOXGI_BUILD_DIR=build-asan ./scripts/build.sh -DVOXGI_SANITIZE_INPUT=ON > build-asan.log 2>&1 ||
  { tail -40 build-asan.log; exit 1; }
rm -f build-asan.log
echo "sanitize: build took $(( $(date +%s) - start )) s"
export EGL_PLATFORM=surfaceless
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
cd build-asan
start=$(date +%s)
status=0
if [ -z "${DISPLAY:-}" ] && command -v xvfb-run > /dev/null; then
  xvfb-run -a -s "-screen 0 1280x1024x24" ctest --output-on-failure -j"$(nproc)" --timeout 900 "$@" || status=$?
else
  ctest --output-on-failure -j"$(nproc)" --timeout 900 "$@" || status=$?
fi
echo "sanitize: tests took $(( $(date +%s) - start )) s"
exit $status
