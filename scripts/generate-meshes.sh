#!/usr/bin/env bash
# Regenerates the generated meshes of cases/meshes/ with `rayint generate-mesh` (analytic fields;
# src/rayint/mesh/mesh_generators.hpp). Each file's title line says what it is and how it was made.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
rayint="${RAYINT:-${RAYINT_BUILD_DIR:-$root/build}/rayint}"
out="$root/cases/meshes"
mkdir -p "$out"
"$rayint" generate-mesh ball --n 4 -o "$out/ball.vtk"              #   3,072 tets, s = 1 - |x|
"$rayint" generate-mesh ball --n 13 -o "$out/ball-100k.vtk"        # 105,456 tets, s = 1 - |x|
"$rayint" generate-mesh linear-box --n 3 --seed 1 -o "$out/linear-box.vtk"  # 1,296 tets, linear s
"$rayint" generate-mesh ring --n 2 -o "$out/ring.vtk"              #   4,032 tets, non-convex
