#!/usr/bin/env bash
# Optional (not run by CI; ~30-60 min on a shared 2-core machine): how rayint's load, traversal
# build, render and peak memory scale with the size of a tetrahedral mesh, beside VTK's
# unstructured-grid volume mappers on the same meshes (issue 33). Regenerates reports/scaling/
# (README.md, results.json, scaling.png).
# Installs what it needs when missing, as scripts/vtk-render.sh does: Debian's python3-vtk9 (VTK's
# mappers and the .vtu writer), xvfb (an X display for VTK's OpenGL window), python3-meshio (the
# .msh writer) and python3-matplotlib (the figure).
# Usage: scripts/scaling.sh [--before OLD_RAYINT] [--sizes 6 13 28 60] [other scaling.py args]
# Meshes go to $SCALING_WORK (default /tmp/rayint-scaling), never into the repository; N = 60
# (10.4M tets) needs ~8 GB of memory and ~2 GB of disk there.
set -euo pipefail
cd "$(dirname "$0")/.."
WORK=${SCALING_WORK:-/tmp/rayint-scaling}

. scripts/script-setup.sh
apt_install_missing python3-vtk9 xvfb python3-meshio python3-matplotlib

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >&2
cmake --build build -j2 --target rayint_cli >&2

# The sizes asked for (default 6 13 28: 10k, 105k, 1.05M tets).
sizes=(6 13 28)
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  if [ "${args[$i]}" = "--sizes" ]; then
    sizes=()
    for ((j = i + 1; j < ${#args[@]}; j++)); do
      case "${args[$j]}" in --*) break ;; *) sizes+=("${args[$j]}") ;; esac
    done
  fi
done
mkdir -p "$WORK"
for n in "${sizes[@]}"; do
  [ -f "$WORK/ball-$n.vtk" ] || build/rayint generate-mesh ball --n "$n" -o "$WORK/ball-$n.vtk"
  [ -f "$WORK/ball-$n.msh" ] || /usr/bin/python3 scripts/big_meshes.py "$WORK/ball-$n.vtk"
done

xvfb-run -a -s "-screen 0 640x480x24" /usr/bin/python3 scripts/scaling.py \
  --rayint build/rayint --work "$WORK" --out reports/scaling "$@"
/usr/bin/python3 scripts/scaling_report.py reports/scaling
echo "reports/scaling/README.md written" >&2
