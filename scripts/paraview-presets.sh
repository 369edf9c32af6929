#!/usr/bin/env bash
# Regenerates tests/data/tf/paraview-5.11-* from ParaView itself (scripts/paraview-presets.py says
# what each file holds). Needs Debian's paraview and python3-paraview (pvpython). The tests do not:
# they read the committed files, so neither package is in scripts/install-deps.sh.
#
# python3-paraview conflicts with python3-vtk9 (both ship vtkmodules/); where python3-vtk9 must
# stay, set PVROOT to an extracted python3-paraview instead of installing it:
#   apt-get download python3-paraview && dpkg -x python3-paraview_*.deb /opt/pv
#   PVROOT=/opt/pv scripts/paraview-presets.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:-$here/../tests/data/tf}"
home="$(mktemp -d)"  # ParaView keeps imported presets in the user's settings: not in $HOME
trap 'rm -rf "$home"' EXIT
if [ -n "${PVROOT:-}" ]; then
  export PYTHONPATH="$PVROOT/usr/lib/python3/dist-packages"
  pvpython="$PVROOT/usr/bin/pvpython3.11"
else
  pvpython="$(command -v pvpython)"
fi
HOME="$home" XDG_CONFIG_HOME="$home" "$pvpython" --force-offscreen-rendering "$here/paraview-presets.py" "$out"
