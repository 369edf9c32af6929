#!/usr/bin/env bash
# Set-up command 2: install, build, and pass the test suite.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh" --test
"$root/scripts/build.sh"
# The suite needs torch (installed above): its gradcheck test fails rather than skips without it.
export RAYINT_REQUIRE_TORCH=1
ctest --test-dir "${RAYINT_BUILD_DIR:-$root/build}" --output-on-failure -j "$(nproc)"
