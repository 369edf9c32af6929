#!/usr/bin/env bash
# Builds the whole test suite (and the rayint executable the CLI tests run) with
# AddressSanitizer + UndefinedBehaviorSanitizer (-DRAYINT_SANITIZE=ON) in its own build directory
# (RAYINT_SANITIZE_BUILD_DIR, default build-sanitize/) and runs all of it with CTest. Any
# sanitizer report fails the test it occurs in (UBSan halts on the first error; LeakSanitizer is
# on). Extra arguments go to ctest, e.g. `scripts/sanitize.sh -R check`.
# The 50-digit reference is several times slower under ASan; the time is printed at the end.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${RAYINT_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRAYINT_SANITIZE=ON \
  -DRAYINT_BUILD_BENCHMARKS=OFF -DRAYINT_BUILD_FUZZERS=OFF >/dev/null
start=$(date +%s)
cmake --build "$build" -j "$(nproc)"
built=$(date +%s)
export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:strict_init_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
# The exported rayint::rayint target carries -fsanitize when RAYINT_SANITIZE is on, so the package
# test's consumer project links the sanitizer runtimes by itself.
status=0
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@" || status=$?
done=$(date +%s)
echo "sanitize.sh: build $((built - start)) s, tests $((done - built)) s (ASan + UBSan, $build)"
if [ "$status" -ne 0 ]; then
  echo "sanitize.sh: FAILED (ctest exit status $status)" >&2
  exit "$status"
fi
echo "sanitize.sh: all tests passed under ASan + UBSan"
