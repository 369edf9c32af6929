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
cmake --build build -j2 --target rayint_cli >&2

/usr/bin/python3 scripts/vtk/vtk_image_render.py self-check
# One X server for the whole run: rayint converge's --command renders inherit its DISPLAY.
xvfb-run -a -s "-screen 0 640x480x24" /usr/bin/python3 scripts/vtk/vtk_image_render.py run \
  --rayint build/rayint --out reports/vtk-image-render "$@"
/usr/bin/python3 reports/vtk-image-render/make_report.py reports/vtk-image-render > reports/vtk-image-render/README.md
echo "reports/vtk-image-render/README.md written" >&2
