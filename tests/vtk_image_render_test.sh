#!/usr/bin/env bash
# CTest vtk_image_render_translation (optional VTK part of issue 32): the translation checks of
# scripts/vtk/vtk_image_render.py (transfer function, camera, float read-back by digit passes,
# constant-volume renders of VTK's three image mappers against the closed form).
# Skipped (exit 77, CTest SKIP_RETURN_CODE) when Debian's python3-vtk9 or xvfb-run is missing:
# the VTK part is optional and not needed by ./scripts/test.sh. A check that runs and fails exits 1.
set -u
src=${1:?usage: vtk_image_render_test.sh SOURCE_DIR}
if ! /usr/bin/python3 -c "import vtk" >/dev/null 2>&1; then
  echo "SKIP: /usr/bin/python3 has no vtk module (apt-get install python3-vtk9)"; exit 77
fi
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIP: xvfb-run is missing (apt-get install xvfb)"; exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
xvfb-run -a -s "-screen 0 640x480x24" /usr/bin/python3 "$src/scripts/vtk/vtk_image_render.py" \
  translation-check --dir "$tmp"
