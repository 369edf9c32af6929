#!/bin/sh
# Regenerates reports/figures/: Max's (1995) cloud figure set rendered by `rayint render` at
# 512 x 512 on 2 threads, each with its per-effect cost and its error against the references on
# 8 x 8 pixels (the multiple-scattering figure: the shadowed one plus multiple scattering, whose
# reference is Monte Carlo), the all-effects cost table, and the two-pass vs shadow-ray sweep (64 x 64 image,
# errors on 6 x 6 pixels, references once). Then reports/figures/README.md and the plot.
# Usage: scripts/figures.sh [BUILD_DIR]   (default build/)
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
RAYINT=$BUILD/rayint
OUT=$ROOT/reports/figures
mkdir -p "$OUT"
cd "$ROOT"
for s in cloud-absorption cloud-emission cloud-emission-absorption cloud-single-scattering \
         cloud-single-scattering-shadows cloud-single-scattering-two-pass \
         cloud-multiple-scattering-figure; do
  echo "== $s" >&2
  "$RAYINT" render "cases/scenes/$s.json" -o "$OUT/$s.png" --stats "$OUT/$s.json" --errors 8 --threads 2 --quiet
done
# The per-effect cost table: every effect at once, without the (expensive) references.
"$RAYINT" render cases/scenes/cloud-all-effects.json -o "$OUT/cloud-all-effects.png" \
    --stats "$OUT/cloud-all-effects.json" --threads 2 --quiet
# The sweep scene: the shadowed figure at 64 x 64 (small, so that the sweep fits; the fixed cost of the two-pass light grid weighs more here than at 512 x 512).
SWEEP_SCENE=$OUT/sweep-scene.json
/usr/bin/python3 - "$ROOT" "$SWEEP_SCENE" <<'PY'
import json, sys
root, out = sys.argv[1], sys.argv[2]
d = json.load(open(root + "/cases/scenes/cloud-single-scattering-shadows.json"))
d["name"] = "cloud-single-scattering-shadows-64"
d["camera"]["width"] = d["camera"]["height"] = 64
d["background"]["image"] = "../../cases/scenes/ground.png"
json.dump(d, open(out, "w"), indent=2)
PY
set --
for n in 16 32 64 128; do
  set -- "$@" --config "single_scattering=riemann:n=$n,shadows=shadow_rays:n=$n"
done
for n in 32 64; do
  for g in 32 64 128; do
    set -- "$@" --config "single_scattering=riemann:n=$n,shadows=two_pass:grid=$g"
  done
done
echo "== sweep" >&2
"$RAYINT" scene-sweep "$SWEEP_SCENE" --errors 6 --threads 2 --quiet "$@" -o "$OUT/sweep.json"
# The matched-error pair of the sweep (max error ~0.013 of the peak), at the figure's 512 x 512,
# without references: shadow rays n = 32 against the two-pass grid 128^3.
echo "== matched pair at 512 x 512" >&2
"$RAYINT" render cases/scenes/cloud-single-scattering-shadows.json -o "$OUT/matched.png" --threads 2 --quiet \
    --method single_scattering=riemann:n=32 --method shadows=shadow_rays:n=32 --stats "$OUT/matched-shadow_rays_n_32.json"
"$RAYINT" render cases/scenes/cloud-single-scattering-shadows.json -o "$OUT/matched.png" --threads 2 --quiet \
    --method single_scattering=riemann:n=32 --method shadows=two_pass:grid=128 --stats "$OUT/matched-two_pass_grid_128.json"
rm -f "$OUT/matched.png"
/usr/bin/python3 "$ROOT/scripts/figures_report.py" "$OUT"
