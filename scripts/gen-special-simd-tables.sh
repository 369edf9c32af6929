#!/bin/sh
# Regenerates src/rayint/special/simd_tables.cpp (the vector erfcx/Dawson tables) from the
# 50-digit reference. Usage: scripts/gen-special-simd-tables.sh [build-dir]
set -eu
cd "$(dirname "$0")/.."
build=${1:-build}
cmake --build "$build" --target gen_special_simd_tables
"$build"/tools/gen_special_simd_tables > src/rayint/special/simd_tables.cpp.new
mv src/rayint/special/simd_tables.cpp.new src/rayint/special/simd_tables.cpp
