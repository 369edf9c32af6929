#!/usr/bin/env bash
# Set-up command 1: install what is missing, build the rayint executable (only it: no tests or
# benchmarks), and evaluate the bundled case corpus against the 50-digit reference (summary table).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
RAYINT_BUILD_TARGET=rayint_cli "$root/scripts/build.sh"
cd "$root"  # the case files name their meshes relative to cases/
"${RAYINT_BUILD_DIR:-$root/build}/rayint" eval cases --format table
