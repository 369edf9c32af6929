#!/bin/bash
# The load and memory part of scripts/scaling.py without VTK, one run per binary (issue 33,
# reports/scaling/NOTES.md "Round 2"): for each ball-N.{vtk,vtu,msh} in $WORK (made by
# scripts/scaling.sh or `rayint generate-mesh ball --n N` + scripts/big_meshes.py), prints
#   LABEL N FMT read|quick|load|render512 USER_S SYS_S PEAK_RSS_KB
# read = `mesh info`, quick = `mesh info --quick-check`, load = `render` at 16 x 16,
# render512 = `render` at 512 x 512 on 2 threads (.vtk only).
# usage: WORK=/tmp/rayint-scaling [SIZES="6 13 28"] [FMTS="vtk vtu msh"] [NORENDER=1] \
#        scripts/load_memory.sh BUILD/rayint LABEL
set -euo pipefail
BIN=$(readlink -f "$1"); L=$2
cd "${WORK:-/tmp/rayint-scaling}"
mk() { # n size fmt
cat > case-$1-$3-$2.json <<J
{"name": "scaling", "transfer_function": {"density": [[0.0, 0.2], [0.3, 2.0], [0.6, 0.5], [1.0, 4.0]], "color": {"r": [[0.0, 1.0], [0.5, 0.2], [1.0, 1.5]], "g": [[0.0, 0.1], [0.5, 1.0], [1.0, 0.3]], "b": [[0.0, 0.4], [1.0, 0.9]]}}, "mesh_file": "ball-$1.$3", "background": [0.05, 0.05, 0.1], "camera": {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 40, "width": $2, "height": $2}}
J
}
for n in ${SIZES:-6 13 28}; do
  for fmt in ${FMTS:-vtk vtu msh}; do
    mk $n 16 $fmt
    /usr/bin/time -f "$L $n $fmt read %U %S %M" $BIN mesh info ball-$n.$fmt --format json >/dev/null
    /usr/bin/time -f "$L $n $fmt quick %U %S %M" $BIN mesh info ball-$n.$fmt --quick-check --format json >/dev/null
    /usr/bin/time -f "$L $n $fmt load %U %S %M" $BIN render case-$n-$fmt-16.json -o /tmp/perf_sc/o16.png -q
  done
  if [ -z "${NORENDER:-}" ]; then
    mk $n 512 vtk
    /usr/bin/time -f "$L $n vtk render512 %U %S %M" $BIN render case-$n-vtk-512.json -o /tmp/perf_sc/o512-$L-$n.png -q --threads 2
  fi
done
