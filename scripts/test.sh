#!/usr/bin/env bash
# Set-up command 2: install, build, and pass the test suite.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/build.sh"
ctest --test-dir "${RAYINT_BUILD_DIR:-$root/build}" --output-on-failure -j "$(nproc)"
