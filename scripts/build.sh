#!/usr/bin/env bash
# Configures and builds rayint into build/ (or $RAYINT_BUILD_DIR), Release by default.
# RAYINT_BUILD_TARGET=rayint_cli builds only the executable (scripts/run.sh); unset: everything
# (tests, benchmarks, the Python module; scripts/test.sh). Extra arguments go to the configure step.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${RAYINT_BUILD_DIR:-$root/build}"
"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" "$@" >/dev/null
cmake --build "$build" -j "$(nproc)" ${RAYINT_BUILD_TARGET:+--target "$RAYINT_BUILD_TARGET"}
