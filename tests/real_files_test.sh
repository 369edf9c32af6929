#!/usr/bin/env bash
# CTest real_files (labels optional, real-files): issue 27's real-files corpus is made with the real
# tools (scripts/real-files/make-corpus.sh: gmsh, TetGen, meshio, VTK 9.1; ParaView's part only when
# pvpython is found) and rayint runs on every file (count.py). Fails if any file gives an unclear
# outcome (a crash, a signal, a time-out, exit 1, a multi-line or nameless error) or if a
# tetrahedral mesh's integral differs by more than 1e-6 from the independent route on VTK's own
# reading (crosscheck_vtk.py --gate-tets). Skips (exit 77) when gmsh, tetgen, python3-vtk9 or
# python3-meshio is missing.
#   real_files_test.sh RAYINT SOURCE_DIR
set -uo pipefail
rayint=$(readlink -f "$1") src=$(readlink -f "$2")
for tool in gmsh tetgen; do
  command -v "$tool" >/dev/null || { echo "real_files: SKIP: $tool not found (apt-get install $tool)"; exit 77; }
done
/usr/bin/python3 -c "import vtk, meshio" 2>/dev/null || { echo "real_files: SKIP: python3-vtk9 or python3-meshio missing"; exit 77; }
T=$(mktemp -d /tmp/rayint-real-files.XXXXXX)
trap 'rm -rf "$T"' EXIT
"$src/scripts/real-files/make-corpus.sh" "$T/corpus" > /dev/null 2> "$T/make.log" || { cat "$T/make.log" >&2; echo "real_files: FAIL: make-corpus.sh" >&2; exit 1; }
/usr/bin/python3 "$src/scripts/real-files/count.py" "$rayint" "$T/corpus" -o "$T/results.json" --fail-on-unclear > "$T/count.md"
rc=$?
grep -A4 "^| kind | files" "$T/count.md" | head -5
sed -n '/### Unclear/,/### Cross-checks/p' "$T/count.md"
[ $rc = 0 ] || { echo "real_files: FAIL: unclear outcomes (above)" >&2; exit 1; }
/usr/bin/python3 "$src/scripts/real-files/crosscheck_vtk.py" "$T/results.json" --gate-tets 2>&1 | tail -1
[ "${PIPESTATUS[0]}" = 0 ] || { echo "real_files: FAIL: a tetrahedral mesh differs from VTK's reading" >&2; exit 1; }
echo "real_files: ok"
