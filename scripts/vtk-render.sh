#!/usr/bin/env bash
# Optional (not run by CI): render rayint's mesh cases with VTK's own volume mappers
# (vtkUnstructuredGridVolumeRayCastMapper with each of its four ray integrators, and
# vtkProjectedTetrahedraMapper), read the images back as floats and gate them with
# `rayint check --candidate-image`; regenerates reports/vtk-render/ (figures, tables, README).
# Installs what it needs when missing: Debian's python3-vtk9 (VTK 9.1's Python bindings),
# xvfb (VTK's OpenGL render window needs an X display; xvfb-run gives it one) and
# python3-matplotlib (the figures). Usage: scripts/vtk-render.sh [extra args for vtk_render.py]
set -euo pipefail
cd "$(dirname "$0")/.."

. scripts/script-setup.sh
vtk_report_setup rayint

# The translation checks first (camera and transfer function; no display needed).
/usr/bin/python3 scripts/vtk_render.py --self-check
xvfb-run -a -s "-screen 0 640x480x24" /usr/bin/python3 scripts/vtk_render.py \
  --rayint build/rayint --out reports/vtk-render "$@"
/usr/bin/python3 reports/vtk-render/make_vtk_render_report.py reports/vtk-render > reports/vtk-render/README.md
echo "reports/vtk-render/README.md written" >&2
