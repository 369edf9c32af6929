#!/usr/bin/env bash
# Optional (not run by CI): render .vti volumes with VTK's image volume mappers
# (vtkFixedPointVolumeRayCastMapper: its own ray-cast image and its displayed frame;
# vtkGPUVolumeRayCastMapper; vtkSmartVolumeMapper) under Xvfb/llvmpipe, read the images back as
# floats, gate them with `rayint check --candidate-image` and measure their convergence with the
# sample distance with `rayint converge --command`; regenerates reports/vtk-image-render/.
# Installs what it needs when missing: python3-vtk9 (VTK 9.1's Python bindings), xvfb (VTK's
# OpenGL window needs an X display) and python3-matplotlib (the figures).
# Usage: scripts/vtk-image-render.sh [extra args for `vtk_image_render.py run`]
set -euo pipefail
cd "$(dirname "$0")/.."

. scripts/script-setup.sh
vtk_report_setup rayint_cli

/usr/bin/python3 scripts/vtk/vtk_image_render.py self-check
# One X server for the whole run: rayint converge's --command renders inherit its DISPLAY.
xvfb-run -a -s "-screen 0 640x480x24" /usr/bin/python3 scripts/vtk/vtk_image_render.py run \
  --rayint build/rayint --out reports/vtk-image-render "$@"
/usr/bin/python3 reports/vtk-image-render/make_report.py reports/vtk-image-render > reports/vtk-image-render/README.md
echo "reports/vtk-image-render/README.md written" >&2
