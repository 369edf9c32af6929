#!/usr/bin/env bash
# Regenerates tests/fixtures/images/: one small test image written by tools rayint did not write,
# so the float-image readers (src/rayint/render/float_image.hpp) are tested on real files:
#   grad.ppm           the source, 8-bit ASCII PPM (P3), written below
#   grad_f8.npy        NumPy (np.save) float64, shape (3, 4, 3)
#   grad_f4.npy        NumPy (np.save) float32, shape (3, 4, 3)
#   grad_grey.npy      NumPy (np.save) float64, shape (3, 4) (grey)
#   grad_netpbm_be.pfm netpbm's pamtopfm -endian=big (big-endian PFM, rows bottom to top)
#   grad_netpbm_le.pfm netpbm's pamtopfm -endian=little (little-endian PFM)
#   grad_oiio.exr      OpenImageIO's oiiotool (32-bit float EXR)
#   grad_oiio_half.exr OpenImageIO's oiiotool (16-bit half EXR)
#   grad_rgba_oiio.exr OpenImageIO's oiiotool, float RGBA: the gradient plus an "A" channel filled
#                      left to right from 0.25 to 1 (0.25, 0.5, 0.75, 1 by column)
# Pixel (x, y) with y = 0 the top row, channel c, holds v/255 with v = 20x + 60y + 3c + 1 (ints
# < 256, so every file holds the same values up to float rounding); tests/test_float_images.cpp
# checks them at every pixel. Optional tools (only for regenerating these committed files):
# Debian's netpbm, openimageio-tools, python3-numpy; installed here when missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$root/tests/fixtures/images"
. "$root/scripts/script-setup.sh"
apt_install_missing netpbm openimageio-tools python3-numpy
mkdir -p "$out"
cd "$out"
{
  echo "P3"; echo "4 3"; echo "255"
  for y in 0 1 2; do
    for x in 0 1 2 3; do
      for c in 0 1 2; do printf '%d ' $((20 * x + 60 * y + 3 * c + 1)); done
    done
    echo
  done
} > grad.ppm
pamtopfm -endian=big grad.ppm > grad_netpbm_be.pfm
pamtopfm -endian=little grad.ppm > grad_netpbm_le.pfm
oiiotool grad.ppm -d float -o grad_oiio.exr
oiiotool grad.ppm -d half -o grad_oiio_half.exr
oiiotool grad.ppm -d float --pattern "fill:left=0.25:right=1" 4x3 1 --chnames A --chappend -o grad_rgba_oiio.exr
/usr/bin/python3 - <<'PY'
import numpy as np
y, x, c = np.meshgrid(np.arange(3), np.arange(4), np.arange(3), indexing="ij")
a = (20 * x + 60 * y + 3 * c + 1) / 255.0
np.save("grad_f8.npy", a.astype(np.float64))
np.save("grad_f4.npy", a.astype(np.float32))
np.save("grad_grey.npy", a[:, :, 0].astype(np.float64))
PY
ls -l "$out"
