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

./scripts/install-deps.sh
missing=()
for pkg in python3-vtk9 xvfb python3-matplotlib; do
  dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >&2
cmake --build build -j2 --target rayint >&2

# The translation checks first (camera and transfer function; no display needed).
/usr/bin/python3 scripts/vtk_render.py --self-check
xvfb-run -a -s "-screen 0 640x480x24" /usr/bin/python3 scripts/vtk_render.py \
  --rayint build/rayint --out reports/vtk-render "$@"
/usr/bin/python3 reports/vtk-render/make_vtk_render_report.py reports/vtk-render > reports/vtk-render/README.md
echo "reports/vtk-render/README.md written" >&2
