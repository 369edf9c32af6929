#!/usr/bin/env bash
# The VTK variant in one command: installs libvtk9-dev if missing, configures and builds
# build-vtk/ with -DRAYINT_WITH_VTK=ON, runs its tests (CTest, incl. the [vtk] tests), and
# regenerates reports/vtk/ (per-regime error tables of VTK's integrators next to exact, cost per
# piece from the same run). Usage: scripts/vtk.sh [COUNT] [SEED]   (defaults 40000 pieces, seed 8)
set -euo pipefail
cd "$(dirname "$0")/.."
count=${1:-40000}   # split evenly over the 4 regimes: 10,000 pieces each
seed=${2:-8}

./scripts/install-deps.sh
. scripts/script-setup.sh
apt_install_missing libvtk9-dev

cmake -S . -B build-vtk -DRAYINT_WITH_VTK=ON -DRAYINT_BUILD_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=Release >&2
cmake --build build-vtk -j2 >&2
(cd build-vtk && ctest -R '^vtk[.]' --output-on-failure -j2) >&2

mkdir -p reports/vtk
# vtk_preint builds its table per sample (each stress piece has its own transfer functions), so
# the stress run uses a 32 x 32 x 64 table; the default 128 x 128 x 256 is measured in eval.
methods="exact,vtk_linear,vtk_partial_preint,vtk_homogeneous,vtk_preint:incremental=1:scalar_res=32:length_res=64:max_length=1000,vtk_preint:incremental=0:scalar_res=32:length_res=64:max_length=1000"
build-vtk/rayint stress --count "$count" --seed "$seed" --threads 2 \
  --regime tau_moderate,tau_thin,q2_near_zero_pos,tau_thick --methods "$methods" \
  --json -o reports/vtk/stress.json --no-worst --quiet
# Cost per segment and error, VTK's methods and ours, in ONE eval run (same process, same rays):
# 50-segment rays with breakpoints crossed and a background (cases/many-segments-background.json).
ours="exact,riemann:n=4,riemann:n=16,riemann:n=64,riemann:n=256,rk4:n=4,ode:rtol=1e-6,eq5,eq8,psi_table:size=512,psi_table:size=512:lookup=linear,preintegrated"
build-vtk/rayint eval cases/many-segments-background.json cases/medical-ct.json cases/paper-figure-2.json \
  --methods "$ours,vtk_linear,vtk_partial_preint,vtk_homogeneous,vtk_preint:incremental=1,vtk_preint:incremental=0" \
  --format json -o reports/vtk/cost.json
uptime > reports/vtk/load.txt
/usr/bin/python3 reports/vtk/make_vtk_report.py reports/vtk/stress.json reports/vtk/load.txt \
  reports/vtk/cost.json reports/vtk/error_vs_time.png > reports/vtk/README.md
echo "reports/vtk/README.md written" >&2
