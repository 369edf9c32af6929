#!/usr/bin/env bash
# Set-up command 1: install, build, and evaluate the bundled case corpus (summary table).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/build.sh"
"${RAYINT_BUILD_DIR:-$root/build}/rayint" eval "$root/cases" --format table
