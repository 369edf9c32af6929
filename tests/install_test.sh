#!/usr/bin/env bash
# CTest `install_gate`: `cmake --install` puts the executable, the bundled cases and the gate
# configuration under a prefix, and the installed `rayint gate` finds them from any directory
# (cli/data_dir.hpp). Usage: install_test.sh BUILD_DIR
set -euo pipefail
build="$1"
T="$(mktemp -d)"
trap 'rm -rf "$T"' EXIT
cmake --install "$build" --prefix "$T/prefix" >/dev/null
for f in bin/rayint share/rayint/cases/gates.json share/rayint/cases/paper-figure-2.json \
         share/rayint/cases/meshes/ball.vtk share/rayint/cases/baselines share/doc/rayint/LICENSE; do
  [ -e "$T/prefix/$f" ] || { echo "install_gate: $f was not installed"; exit 1; }
done
mkdir "$T/elsewhere"
cd "$T/elsewhere"
# The installed config's corpus part, on the installed cases (the stress part is the gate test's).
/usr/bin/python3 - "$T/prefix/share/rayint/cases/gates.json" "$T/small-gates.json" <<'PY'
import json, sys
cfg = json.load(open(sys.argv[1]))
small = {"corpus": {"cases": [sys.argv[1].rsplit("/", 1)[0] + "/paper-figure-2.json"],
                    "methods": {"exact": cfg["corpus"]["methods"]["exact"]}}}
json.dump(small, open(sys.argv[2], "w"))
PY
"$T/prefix/bin/rayint" gate --config "$T/small-gates.json" -q > out.txt || { cat out.txt; echo "install_gate: gate on the installed cases failed"; exit 1; }
# Without --config, outside a source tree: the installed gates.json is the default. A missing
# default is exit 2 at once ("cases/gates.json: cannot open"); found, the gate starts its corpus
# run (progress on stderr), which this test does not wait for (the CTest `gate` runs it whole).
status=0
timeout 20 "$T/prefix/bin/rayint" gate --threads 1 > default.txt 2> default.err || status=$?
if [ "$status" = 2 ]; then cat default.err; echo "install_gate: the installed default config was not found"; exit 1; fi
grep -q "^gate: " default.err || { cat default.err; echo "install_gate: the default gate showed no progress"; exit 1; }
[ -z "$(ls -A "$T/elsewhere" | grep -v -e out.txt -e default.txt -e default.err)" ] || { ls "$T/elsewhere"; echo "install_gate: gate wrote into the working directory"; exit 1; }
echo "install_gate: PASS (installed rayint gate runs on share/rayint/cases from another directory, exit $status)"
