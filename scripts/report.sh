#!/usr/bin/env bash
# One command for reports/: builds rayint, runs the accuracy/cost sweep over every cases/*.json
# (`rayint bench` -> reports/bench.json, progress on stderr), then draws reports/error_vs_time.png,
# reports/error_vs_knob.png and writes reports/README.md with Debian's python3-matplotlib
# (/usr/bin/python3; scripts/install-deps.sh, called by build.sh, installs it if missing).
# Extra arguments go to `rayint bench`, e.g.  scripts/report.sh --methods riemann,ode
# Timings are single-threaded wall-clock times: run it on a quiet machine (the report states the
# load average at the start and the end of the sweep).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${RAYINT_BUILD_DIR:-$root/build}"
"$root/scripts/build.sh"
cd "$root"
echo "load average before the sweep: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
# --method-seconds: a safety net so that no single method can run away with the sweep (the whole
# default sweep takes a few minutes on a quiet 2-core machine); a cut is recorded in the report.
"$build/rayint" bench --method-seconds 300 "$@" -o reports/bench.json
/usr/bin/python3 reports/make_report.py reports/bench.json
